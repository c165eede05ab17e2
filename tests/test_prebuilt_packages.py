"""scripts/prebuilt_packages.py: a package built once per machine is copied into any workspace, relocated."""

import os
import subprocess
import sys
import time
from pathlib import Path

import setup_scripts

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = setup_scripts.SCRIPTS / 'prebuilt_packages.py'
prebuilt = setup_scripts.load('prebuilt_packages')

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
    prebuilt.store(one, cache, package, digest, RECIPE)

    other_package = workspace(two)
    for built in (two / 'install').iterdir():  # a workspace with an older, symlinked install of it
        for path in built.rglob('*'):
            if path.is_file():
                path.write_text('older build')
    assert digest_of(two, other_package) == digest  # the workspace's path is not in the digest
    for path in cache.rglob('*'):  # kept long ago
        os.utime(path, (1e9, 1e9))
    restoring = time.time()
    assert prebuilt.restore(two, cache, other_package, digest, RECIPE)

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


def python_workspace(root: Path) -> Path:
    """A workspace at root with a Python package built with --symlink-install, as colcon leaves it."""
    package = root / 'src' / 'course' / 'olive_servo'
    (package / 'olive_servo').mkdir(parents=True)
    (package / 'olive_servo' / 'control_servo.py').write_text('print(1)\n')
    (package / 'setup.py').write_text('setup()\n')
    (package / 'package.xml').write_text('<package><name>olive_servo</name>'
                                         '<exec_depend>olive_interfaces</exec_depend></package>\n')
    (root / 'requirements.txt').write_text('rclpy==9.9\n')
    build, installed = root / 'build' / 'olive_servo', root / 'install' / 'olive_servo'
    build.mkdir(parents=True)
    (build / 'olive_servo').symlink_to(package / 'olive_servo')
    (build / 'setup.py').symlink_to(package / 'setup.py')
    (installed / 'share' / 'olive_servo').mkdir(parents=True)
    (installed / 'share' / 'olive_servo' / 'setup.py').symlink_to(build / 'setup.py')
    (installed / 'share' / 'olive_servo' / 'relative').symlink_to('../../lib')
    (installed / 'lib' / 'python3.11' / 'site-packages').mkdir(parents=True)
    (installed / 'lib' / 'python3.11' / 'site-packages' / 'olive-servo.egg-link').write_text(f'{build}\n.')
    return package


def test_a_symlink_install_is_restored_with_its_build_folder_and_links_into_the_new_workspace(tmp_path):
    cache, recipe = tmp_path / 'cache', 'colcon build --symlink-install'
    one, two = tmp_path / 'one', tmp_path / 'two'
    package = python_workspace(one)
    digest = prebuilt.package_digest(one, package, recipe, TOOLS)
    prebuilt.store(one, cache, package, digest, recipe)
    other_package = python_workspace(two)
    prebuilt.forget_build(two, 'olive_servo')
    assert prebuilt.restore(two, cache, other_package, digest, recipe)

    build, installed = two / 'build' / 'olive_servo', two / 'install' / 'olive_servo'
    assert (build / 'olive_servo').readlink() == other_package / 'olive_servo'
    assert (installed / 'share' / 'olive_servo' / 'setup.py').readlink() == build / 'setup.py'
    assert (installed / 'share' / 'olive_servo' / 'setup.py').read_text() == 'setup()\n'
    assert os.readlink(installed / 'share' / 'olive_servo' / 'relative') == '../../lib'
    egg_link = installed / 'lib' / 'python3.11' / 'site-packages' / 'olive-servo.egg-link'
    assert egg_link.read_text() == f'{build}\n.'
    assert not list(two.glob('install/.olive_servo-*'))  # no staging left behind
    # The cache holds no workspace's path, in a text or a link.
    for path in cache.rglob('*'):
        if path.is_symlink():
            assert str(one) not in os.readlink(path)
        elif path.is_file():
            assert bytes(one) not in path.read_bytes()


def test_a_build_dependency_is_in_the_digest_and_a_run_dependency_is_not(tmp_path):
    interfaces = workspace(tmp_path)
    servo = python_workspace(tmp_path)
    prebuilt.workspace_packages.cache_clear()

    def digests() -> tuple[str, str]:
        return digest_of(tmp_path, interfaces), digest_of(tmp_path, servo)

    before = digests()
    (interfaces / 'msg' / 'RgbColor.msg').write_text('uint8 r\n')  # olive_servo only runs with it
    after_run_dependency = digests()
    assert after_run_dependency[0] != before[0]
    assert after_run_dependency[1] == before[1]
    manifest = servo / 'package.xml'
    manifest.write_text(manifest.read_text().replace('exec_depend', 'depend'))
    built_against = digest_of(tmp_path, servo)
    (interfaces / 'msg' / 'RgbColor.msg').write_text('uint8 g\n')
    assert digest_of(tmp_path, servo) != built_against


def test_nothing_cached_means_build_it_and_a_second_store_keeps_the_first(tmp_path):
    cache = tmp_path / 'cache'
    package = workspace(tmp_path)
    digest = digest_of(tmp_path, package)
    assert not prebuilt.restore(tmp_path, cache, package, 'f' * 64, RECIPE)
    prebuilt.store(tmp_path, cache, package, digest, RECIPE)
    [kept] = cache.iterdir()
    launcher = kept / 'install' / 'olive_interfaces' / 'lib' / 'olive_interfaces' / 'node'
    launcher.write_text('first')
    prebuilt.store(tmp_path, cache, package, digest, RECIPE)
    assert [path.name for path in cache.iterdir()] == [kept.name]
    assert launcher.read_text() == 'first'


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
    prebuilt.store(tmp_path, not_a_folder, package, digest, RECIPE)
    [line] = capsys.readouterr().err.splitlines()
    assert line.startswith('setup: olive_interfaces is built but not kept for other workspaces'), line
    # The workspace's install stands: the next setup finds it built.
    assert prebuilt.restore(tmp_path, not_a_folder, package, digest, RECIPE)
