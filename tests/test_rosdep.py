"""`rosdep` as the course uses it, against real workspaces, with pip kept away from the real venv.

Installs go to a throwaway --target from a wheel built here (no index, no network), and the pins
come from a requirements.txt in a temporary OWL_ROOT.
"""

import base64
import hashlib
import os
import subprocess
import zipfile
from collections.abc import Sequence
from pathlib import Path

import pytest

SUCCESS = '#All required rosdeps installed successfully'
ERROR_HEADER = ['ERROR: the following packages/stacks could not have their rosdep keys resolved',
                'to system dependencies:']
FAKE_KEY = 'owl_fake_dep'
FAKE_WHEEL = 'ros-owl-fake-dep'

MANIFEST = '''<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.0.0</version>
  <description>test package</description>
  <maintainer email="nobody@nowhere.example">nobody</maintainer>
  <license>MIT</license>
{depends}
  <export><build_type>ament_python</build_type></export>
</package>
'''


def add_package(src: Path, name: str, depend: Sequence[str] = (), test_depend: Sequence[str] = ()) -> None:
    lines = [f'  <depend>{key}</depend>' for key in depend]
    lines += [f'  <test_depend>{key}</test_depend>' for key in test_depend]
    (src / name).mkdir(parents=True)
    (src / name / 'package.xml').write_text(MANIFEST.format(name=name, depends='\n'.join(lines)))


def rosdep(*args: str, cwd: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(['rosdep', *args], capture_output=True, text=True, cwd=cwd, env=env,
                          stdin=subprocess.DEVNULL, timeout=120)


@pytest.fixture
def pinned_env(tmp_path):
    """OWL_ROOT with a requirements.txt pinning the fake wheel; pip only sees a local folder."""
    root = tmp_path / 'owl_root'
    root.mkdir()
    (root / 'requirements.txt').write_text(f'{FAKE_WHEEL}==0.1.0\n')
    wheels = tmp_path / 'wheels'
    wheels.mkdir()
    env = dict(os.environ, OWL_ROOT=str(root), PIP_NO_INDEX='1', PIP_FIND_LINKS=str(wheels),
               PIP_TARGET=str(tmp_path / 'target'), PIP_DISABLE_PIP_VERSION_CHECK='1')
    return env, wheels


def build_wheel(folder: Path, name: str, version: str, module: str) -> None:
    """A minimal pure-Python wheel, enough for pip to install."""
    dist = f'{name.replace("-", "_")}-{version}'
    files = {
        f'{module}/__init__.py': 'VALUE = 1\n',
        f'{dist}.dist-info/METADATA': f'Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n',
        f'{dist}.dist-info/WHEEL': ('Wheel-Version: 1.0\nGenerator: test\nRoot-Is-Purelib: true\n'
                                    'Tag: py3-none-any\n'),
    }
    record = []
    for path, text in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(text.encode()).digest()).rstrip(b'=').decode()
        record.append(f'{path},sha256={digest},{len(text.encode())}')
    record.append(f'{dist}.dist-info/RECORD,,')
    files[f'{dist}.dist-info/RECORD'] = '\n'.join(record) + '\n'
    with zipfile.ZipFile(folder / f'{dist}-py3-none-any.whl', 'w') as wheel:
        for path, text in files.items():
            wheel.writestr(path, text)


def test_course_command_on_a_created_workspace(tmp_path):
    src = tmp_path / 'src'
    src.mkdir()
    created = subprocess.run(['ros2', 'pkg', 'create', 'random_numbers', '--build-type', 'ament_python',
                              '--dependencies', 'rclpy', 'std_msgs'], cwd=src, capture_output=True,
                             text=True, timeout=60)
    assert created.returncode == 0, created.stderr
    add_package(src, 'uses_random_numbers', depend=['random_numbers', 'geometry_msgs'],
                test_depend=['python3-pytest', 'python3-yaml'])
    result = rosdep('install', '-i', '--from-path', 'src', '--rosdistro', 'humble', '-y', cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout == SUCCESS + '\n'
    assert 'Traceback' not in result.stderr
    check = rosdep('check', '--from-paths', 'src', '--ignore-src', cwd=tmp_path)
    assert (check.returncode, check.stdout) == (0, 'All system dependencies have been satisfied\n')


def test_chapter_four_keys_are_satisfied_by_the_pinned_libraries_and_our_cv_bridge(tmp_path):
    # section 4.5's display_camera package, as a student would declare it
    add_package(tmp_path / 'src', 'olive_camera',
                depend=['rclpy', 'sensor_msgs', 'cv_bridge', 'python3-opencv', 'python3-numpy'],
                test_depend=['python3-pytest', 'python3-setuptools'])
    add_package(tmp_path / 'src', 'olive_servo', depend=['python3-pygame', 'python3-yaml', 'python3-pil'])
    # Were anything missing, pip must fail here rather than change the real venv.
    env = dict(os.environ, PIP_NO_INDEX='1', PIP_TARGET=str(tmp_path / 'target'))
    result = rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path, env=env)
    assert (result.returncode, result.stdout) == (0, SUCCESS + '\n'), result.stdout + result.stderr
    check = rosdep('check', '--from-paths', 'src', '--ignore-src', cwd=tmp_path)
    assert (check.returncode, check.stdout) == (0, 'All system dependencies have been satisfied\n')
    add_package(tmp_path / 'src', 'plots', depend=['python3-matplotlib'])  # not pinned: an error
    unpinned = rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path, env=env)
    assert unpinned.returncode == 1
    # Filtered: where the GUI build cannot load, probing cv2 also prints the fallback's notice.
    assert [line for line in unpinned.stderr.splitlines() if line.startswith('plots: ')] == [
        "plots: Cannot locate rosdep definition for [python3-matplotlib] (the Python module 'matplotlib' "
        "is missing and requirements.txt pins no 'matplotlib')"]


def test_without_ignore_src_the_workspaces_own_packages_must_resolve(tmp_path):
    add_package(tmp_path / 'src', 'a_pkg')
    add_package(tmp_path / 'src', 'b_pkg', depend=['a_pkg'])
    result = rosdep('install', '--from-paths', 'src', '-y', cwd=tmp_path)
    assert result.returncode == 1
    assert result.stderr.splitlines() == [*ERROR_HEADER, 'b_pkg: Cannot locate rosdep definition for [a_pkg]']
    assert rosdep('install', '--from-paths', 'src', '-i', '-y', cwd=tmp_path).returncode == 0


def test_simulate_resolves_a_missing_ros_package_to_its_pinned_wheel(tmp_path, pinned_env):
    env, _ = pinned_env
    add_package(tmp_path / 'src', 'needs_fake', depend=[FAKE_KEY, 'rclpy'])
    result = rosdep('install', '-i', '--from-paths', 'src', '-s', cwd=tmp_path, env=env)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == '#[pip] Installation commands:'
    assert lines[1].endswith(f' -m pip install {FAKE_WHEEL}==0.1.0')
    assert len(lines) == 2
    check = rosdep('check', '-i', '--from-paths', 'src', cwd=tmp_path, env=env)
    assert check.returncode == 1
    assert check.stdout.splitlines() == ['System dependencies have not been satisfied:',
                                         f'pip\t{FAKE_WHEEL}==0.1.0']


def test_install_runs_pip_with_the_pin(tmp_path, pinned_env):
    env, wheels = pinned_env
    build_wheel(wheels, FAKE_WHEEL, '0.1.0', FAKE_KEY)
    build_wheel(wheels, FAKE_WHEEL, '0.2.0', FAKE_KEY)  # a newer one that must not be chosen
    add_package(tmp_path / 'src', 'needs_fake', depend=[FAKE_KEY])
    result = rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path, env=env)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.splitlines()[-1] == SUCCESS
    assert f'pip install {FAKE_WHEEL}==0.1.0]' in result.stdout.splitlines()[0]
    assert (tmp_path / 'target' / FAKE_KEY / '__init__.py').is_file()
    assert (tmp_path / 'target' / 'ros_owl_fake_dep-0.1.0.dist-info').is_dir()


def test_a_failing_pip_is_reported(tmp_path, pinned_env):
    env, _ = pinned_env  # no wheel in the folder: pip cannot find the pin
    add_package(tmp_path / 'src', 'needs_fake', depend=[FAKE_KEY])
    result = rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path, env=env)
    assert result.returncode == 1
    assert 'ERROR: the following rosdeps failed to install' in result.stderr
    assert SUCCESS not in result.stdout


def test_without_yes_and_without_a_terminal_nothing_is_installed(tmp_path, pinned_env):
    env, _ = pinned_env
    add_package(tmp_path / 'src', 'needs_fake', depend=[FAKE_KEY])
    result = rosdep('install', '-i', '--from-paths', 'src', cwd=tmp_path, env=env)
    assert result.returncode == 1
    assert result.stderr.strip() == ('ERROR: not installing without confirmation: rerun with -y to let '
                                     'rosdep run pip')
    assert not (tmp_path / 'target').exists()


def test_every_unresolvable_key_is_listed_and_nothing_installed(tmp_path, pinned_env):
    env, _ = pinned_env
    add_package(tmp_path / 'src', 'a_pkg', depend=['no_such_package', FAKE_KEY],
                test_depend=['python3-no-such-module'])
    add_package(tmp_path / 'src', 'b_pkg', depend=['another_missing'])
    result = rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path, env=env)
    assert result.returncode == 1
    errors = result.stderr.splitlines()
    assert errors[:2] == ERROR_HEADER
    assert errors[2] == 'a_pkg: Cannot locate rosdep definition for [no_such_package]'
    assert errors[3].startswith('a_pkg: Cannot locate rosdep definition for [python3-no-such-module]')
    assert errors[4] == 'b_pkg: Cannot locate rosdep definition for [another_missing]'
    assert result.stdout == ''
    assert not (tmp_path / 'target').exists()


def test_robust_mode_goes_on_with_the_resolvable_keys(tmp_path, pinned_env):
    env, _ = pinned_env
    add_package(tmp_path / 'src', 'a_pkg', depend=['no_such_package', FAKE_KEY])
    result = rosdep('install', '-i', '--from-paths', 'src', '-r', '-s', cwd=tmp_path, env=env)
    assert result.returncode == 1
    assert 'Continuing to install resolvable dependencies...' in result.stderr
    assert f'pip install {FAKE_WHEEL}==0.1.0' in result.stdout


def test_dependency_types_and_skip_keys_select_keys(tmp_path):
    add_package(tmp_path / 'src', 'a_pkg', depend=['rclpy'], test_depend=['no_such_test_tool'])
    assert rosdep('install', '-i', '--from-paths', 'src', '-y', cwd=tmp_path).returncode == 1
    for option in (['-t', 'exec', '-t', 'build'], ['--skip-keys', 'no_such_test_tool']):
        result = rosdep('install', '-i', '--from-paths', 'src', '-y', *option, cwd=tmp_path)
        assert (result.returncode, result.stdout) == (0, SUCCESS + '\n'), option
    keys = rosdep('keys', '-i', '--from-paths', 'src', cwd=tmp_path)
    assert keys.stdout.split() == ['no_such_test_tool', 'rclpy']


def test_installed_packages_by_name(tmp_path):
    result = rosdep('check', 'random_number_ps', cwd=tmp_path)
    assert (result.returncode, result.stdout) == (0, 'All system dependencies have been satisfied\n')
    missing = rosdep('check', 'not_installed_pkg', cwd=tmp_path)
    assert missing.returncode == 1
    assert missing.stderr.strip() == ("ERROR: package 'not_installed_pkg' is not installed (to check a "
                                      'source folder, give --from-paths <folder>)')


@pytest.mark.parametrize('command', ['init', 'update'])
def test_init_and_update_have_nothing_to_do(tmp_path, command):
    result = rosdep(command, cwd=tmp_path)
    assert result.returncode == 0
    assert result.stdout.startswith(f'rosdep {command}: nothing to do here.')


def test_bad_input(tmp_path):
    add_package(tmp_path / 'src', 'dup')
    add_package(tmp_path / 'other', 'dup')
    (tmp_path / 'broken' / 'pkg').mkdir(parents=True)
    (tmp_path / 'broken' / 'pkg' / 'package.xml').write_text('<package><name>pkg</nam')
    cases = [
        (['install', '--from-paths', 'nope', '-y'], 1, "ERROR: given path 'nope' does not exist"),
        (['install', '--from-paths', 'src', 'other', '-i'], 1, 'dup'),
        (['check', '--from-paths', 'broken'], 1, 'ERROR: '),
        (['install', '--from-paths', '-y'], 2, 'no packages given'),
        (['install', '--from-paths', 'src', '-t', 'runtime'], 2, "invalid choice: 'runtime'"),
        (['instal', '--from-paths', 'src'], 2, "invalid choice: 'instal'"),
    ]
    for args, code, message in cases:
        result = rosdep(*args, cwd=tmp_path)
        assert result.returncode == code, (args, result.stderr)
        assert message in result.stderr, (args, result.stderr)
        assert 'Traceback' not in result.stderr
        if code == 1:
            assert len(result.stderr.strip().splitlines()) == 1, result.stderr
