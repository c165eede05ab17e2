"""scripts/prebuilt_packages.py: a package built once per machine is copied into any workspace, relocated."""

import importlib.util
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / 'scripts' / 'prebuilt_packages.py'
_spec = importlib.util.spec_from_file_location('prebuilt_packages', SCRIPT)
assert _spec is not None
assert _spec.loader is not None
prebuilt = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(prebuilt)

RECIPE = 'colcon build -DBUILD_TESTING=OFF'
TOOLS = 'cc 12\ncmake 3.25\nPython 3.11'
LIBRARY = b'\x7fELF\0\0 built in /work/one/build/olive_interfaces/x.c\0'


def workspace(root: Path) -> Path:
    """A workspace at root with one message package and its install as a build there leaves it."""
    package = root / 'src' / 'course' / 'olive_interfaces'
    (package / 'msg').mkdir(parents=True, exist_ok=True)
    (package / 'msg' / 'RgbColor.msg').write_text('uint8 r\nuint8 g\nuint8 b\n')
    (package / 'package.xml').write_text('<package><name>olive_interfaces</name></package>\n')
    (root / 'requirements.txt').write_text('rclpy==9.9\n')
    installed = root / 'install' / 'olive_interfaces'
    (installed / 'lib' / 'olive_interfaces').mkdir(parents=True)
    (installed / 'lib' / 'olive_interfaces' / 'node').write_text(f'#!{root}/.venv/bin/python\nprint(1)\n')
    (installed / 'lib' / 'libolive_interfaces.so').write_bytes(LIBRARY.replace(b'/work/one', bytes(root)))
    (installed / 'lib' / '__pycache__').mkdir()
    (installed / 'lib' / '__pycache__' / 'stale.pyc').write_bytes(b'old')
    return package


def digest_of(root: Path, package: Path) -> str:
    return prebuilt.package_digest(root, package, RECIPE, TOOLS)


def test_a_build_stored_from_one_workspace_is_restored_into_another_naming_it(tmp_path):
    cache = tmp_path / 'cache'
    one, two = tmp_path / 'one', tmp_path / 'two'
    package = workspace(one)
    digest = digest_of(one, package)
    prebuilt.store(one, cache, package, digest)

    other_package = workspace(two)
    for built in (two / 'install').iterdir():  # a workspace with an older, symlinked install of it
        for path in built.rglob('*'):
            if path.is_file():
                path.write_text('older build')
    assert digest_of(two, other_package) == digest  # the workspace's path is not in the digest
    for path in cache.rglob('*'):  # kept long ago
        os.utime(path, (1e9, 1e9))
    restoring = time.time()
    assert prebuilt.restore(two, cache, other_package, digest)

    installed = two / 'install' / 'olive_interfaces'
    launcher = (installed / 'lib' / 'olive_interfaces' / 'node').read_text()
    assert launcher == f'#!{two}/.venv/bin/python\nprint(1)\n'
    # A binary keeps its bytes (its build folder is only in debug strings).
    library = (installed / 'lib' / 'libolive_interfaces.so').read_bytes()
    assert library == LIBRARY.replace(b'/work/one', bytes(one))
    assert not (installed / 'lib' / '__pycache__' / 'stale.pyc').exists()  # bytecode is compiled anew
    assert not (installed / prebuilt.RELOCATED).exists()
    # As new as a build made now: owl check takes an install older than its sources for a stale one.
    assert min(path.stat().st_mtime for path in installed.rglob('*') if path.is_file()) >= restoring - 1
    assert prebuilt.stamp(two, 'olive_interfaces').read_text().strip() == digest
    # The cache holds no workspace's path.
    assert not any(bytes(one) in path.read_bytes() and prebuilt.is_text(path.read_bytes())
                   for path in cache.rglob('*') if path.is_file())


def test_any_change_of_a_packages_files_or_the_recipe_is_another_digest(tmp_path):
    package = workspace(tmp_path)
    digest = digest_of(tmp_path, package)
    assert prebuilt.package_digest(tmp_path, package, RECIPE + ' -DX=1', TOOLS) != digest
    assert prebuilt.package_digest(tmp_path, package, RECIPE, TOOLS + '.1') != digest
    (package / 'msg' / 'RgbColor.msg').write_text('uint8 r\n')
    edited = digest_of(tmp_path, package)
    assert edited != digest
    (package / 'msg' / 'RgbColor.msg').rename(package / 'msg' / 'Colour.msg')
    assert digest_of(tmp_path, package) not in (digest, edited)


def test_nothing_cached_means_build_it_and_a_second_store_keeps_the_first(tmp_path):
    cache = tmp_path / 'cache'
    package = workspace(tmp_path)
    digest = digest_of(tmp_path, package)
    assert not prebuilt.restore(tmp_path, cache, package, 'f' * 64)
    prebuilt.store(tmp_path, cache, package, digest)
    [kept] = cache.iterdir()
    (kept / 'lib' / 'olive_interfaces' / 'node').write_text('first')
    prebuilt.store(tmp_path, cache, package, digest)
    assert [path.name for path in cache.iterdir()] == [kept.name]
    assert (kept / 'lib' / 'olive_interfaces' / 'node').read_text() == 'first'


def test_the_command_names_what_to_build_and_refuses_bad_input_in_one_line(tmp_path):
    package = workspace(tmp_path)
    env = {**os.environ, 'XDG_CACHE_HOME': str(tmp_path / 'cache')}
    relative = str(package.relative_to(tmp_path))

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, env=env,
                              check=False)

    first = run('restore', str(tmp_path), RECIPE, relative)
    assert (first.returncode, first.stdout) == (0, relative + '\n'), first.stderr
    assert not (tmp_path / 'install' / 'olive_interfaces').exists()  # an older build goes before building
    workspace(tmp_path)
    assert run('store', str(tmp_path), RECIPE, relative).returncode == 0
    again = run('restore', str(tmp_path), RECIPE, relative)
    assert (again.returncode, again.stdout) == (0, '')
    wrong = run('rebuild', str(tmp_path))
    assert wrong.returncode == 2
    assert 'Traceback' not in wrong.stderr
    assert 'prebuilt_packages.py restore ROOT RECIPE PACKAGE_DIR' in wrong.stderr


def test_a_cache_that_cannot_be_written_keeps_nothing_and_says_so_in_one_line(tmp_path, capsys):
    package = workspace(tmp_path)
    digest = digest_of(tmp_path, package)
    not_a_folder = tmp_path / 'cache'
    not_a_folder.write_text('a file where the cache would be')
    prebuilt.store(tmp_path, not_a_folder, package, digest)
    [line] = capsys.readouterr().err.splitlines()
    assert line.startswith('setup: olive_interfaces is built but not kept for other workspaces'), line
    # The workspace's install stands: the next setup finds it built.
    assert prebuilt.restore(tmp_path, not_a_folder, package, digest)
