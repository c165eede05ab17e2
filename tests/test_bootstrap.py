"""make setup: one clear line for each missing prerequisite, and a fast no-op re-run."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BOOTSTRAP = ROOT / 'scripts' / 'bootstrap.sh'


def run_bootstrap(path_dirs: list[Path], python: str) -> subprocess.CompletedProcess:
    env = {'PATH': os.pathsep.join(map(str, path_dirs)), 'PYTHON': python, 'HOME': os.environ['HOME']}
    bash = shutil.which('bash')
    assert bash is not None
    return subprocess.run([bash, str(BOOTSTRAP)], env=env, capture_output=True,
                          text=True, timeout=60)


def tool_dir(tmp_path: Path, tools: list[str]) -> Path:
    """A folder holding only the named tools of this machine (by symlink)."""
    folder = tmp_path / 'bin'
    folder.mkdir()
    for tool in tools:
        path = shutil.which(tool)
        assert path is not None, tool
        (folder / tool).symlink_to(path)
    return folder


BASICS = ['uname', 'dirname']
COMPILERS = ['cc', 'c++']


@pytest.mark.parametrize(('missing', 'message'), [
    ('cmake', "no cmake found: install it (e.g. 'sudo apt install cmake')."),
    ('cc', 'no C compiler found: install one'),
    ('c++', 'no C++ compiler found: install one'),
])
def test_missing_tool_stops_with_one_line(tmp_path, missing, message):
    present = [tool for tool in [*BASICS, *COMPILERS, 'cmake'] if tool != missing]
    result = run_bootstrap([tool_dir(tmp_path, present)], sys.executable)
    assert result.returncode == 1
    assert result.stdout == ''
    assert len(result.stderr.splitlines()) == 1
    assert result.stderr.startswith('setup: ')
    assert message in result.stderr


def test_unsupported_python_stops_with_one_line(tmp_path):
    fake_python = tmp_path / 'python3.9'
    fake_python.write_text('#!/bin/sh\necho 3.9\n')
    fake_python.chmod(0o755)
    result = run_bootstrap([tool_dir(tmp_path, [*BASICS, *COMPILERS, 'cmake'])], str(fake_python))
    assert result.returncode == 1
    assert len(result.stderr.splitlines()) == 1
    assert 'Python 3.9 found, but the ROS 2 wheels need 3.10-3.13' in result.stderr


def test_missing_python_stops_with_one_line(tmp_path):
    result = run_bootstrap([tool_dir(tmp_path, BASICS)], 'python3-not-here')
    assert result.returncode == 1
    assert result.stderr.strip() == (
        "setup: no 'python3-not-here' found: install Python 3.10-3.13 "
        "(e.g. 'sudo apt install python3 python3-venv').")


def test_rerun_with_nothing_changed_does_nothing(tmp_path):
    # `make test` has just set up; a second setup must find everything in place.
    result = subprocess.run(['bash', str(BOOTSTRAP)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    # One line, so no step ran (each prints what it does); the time it takes is bench material
    # (about a second on an idle machine, several under a loaded suite).
    [line] = result.stdout.splitlines()
    assert re.fullmatch(r"setup: ready in \d+ s\. Next: .*", line), line


@pytest.mark.parametrize('package', ['olive_interfaces', 'turtlesim', 'ros2cli_test_fixtures'])
def test_interface_packages_are_built_for_python_only(package):
    # Python's messages use the C type supports; the venv has no rclcpp to use C++'s (not built).
    libraries = {path.name for path in (ROOT / 'install' / package / 'lib').glob('*.so')}
    assert {f'lib{package}__rosidl_{part}.so' for part in (
        'generator_c', 'typesupport_c', 'typesupport_fastrtps_c', 'typesupport_introspection_c',
        'generator_py')} <= libraries, libraries
    assert not [name for name in libraries if name.endswith('_cpp.so')], libraries
    assert not list((ROOT / 'install' / package / 'include').rglob('*.hpp'))


def test_an_edited_module_needs_no_colcon_build_only_its_bytecode():
    # --symlink-install links the installed files to src/: an edit is in the workspace at once. The
    # module's time is left a second later, as an edit leaves it (its bytecode is then up to date).
    module = ROOT / 'src' / 'course' / 'olive_srvcli' / 'olive_srvcli' / 'client_temperature.py'
    stat = module.stat()
    os.utime(module, ns=(stat.st_atime_ns, stat.st_mtime_ns + 1_000_000_000))
    result = subprocess.run(['bash', str(BOOTSTRAP)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    [line] = result.stdout.splitlines()
    assert re.fullmatch(r"setup: ready in \d+ s \(bytecode \d+ s\)\. Next: .*", line), line
