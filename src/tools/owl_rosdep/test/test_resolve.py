"""owl_rosdep's key resolution and manifest reading as plain functions."""

import os
from pathlib import Path

import pytest
from ament_index_python.packages import get_packages_with_prefixes
from owl_rosdep.cli import make_plan
from owl_rosdep.manifest import ManifestError, dependency_keys, packages_in_paths
from owl_rosdep.resolve import Resolver, load_pins, load_wheel_table, wheel_name
from packaging.utils import canonicalize_name

REQUIREMENTS = Path(__file__).resolve().parents[4] / 'requirements.txt'


def resolver(installed=(), modules=(), programs=(), pins=None, wheels=None):
    return Resolver(pins or {}, wheels or {}, installed_packages=installed,
                    has_module=lambda name: name in modules, has_program=lambda name: name in programs)


def test_pins_follow_markers_and_only_exact_versions(tmp_path):
    requirements = tmp_path / 'requirements.txt'
    requirements.write_text(
        '# comment\n'
        'ros-rclpy==9.1.2\n'
        'numpy==1.0.0; python_version < "3.0"\n'
        'numpy==2.0.0; python_version >= "3.0"\n'
        'PyYAML==6.0.3  # trailing comment\n'
        'loose>=1.0\n'
        '-r other.txt\n'
        'not a requirement !!\n')
    assert load_pins(requirements) == {'ros-rclpy': '9.1.2', 'numpy': '2.0.0', 'pyyaml': '6.0.3'}
    assert load_pins(tmp_path / 'missing.txt') == {}
    assert load_pins(None) == {}


def test_wheel_table_ships_the_jazzy_wheels():
    table = load_wheel_table()
    assert table['ros-rclpy'] == '7.1.6'
    assert 'ros-nav-msgs' in table
    assert not any(name.startswith(('ros-jazzy-', 'ros-cdk-')) for name in table)


def test_wheel_names():
    assert wheel_name('nav_msgs') == 'ros-nav-msgs'
    assert wheel_name('rclpy') == 'ros-rclpy'


def test_installed_packages_tools_and_modules_are_satisfied():
    r = resolver(installed={'rclpy'}, modules={'yaml', 'pytest'}, programs={'cmake'})
    for key in ('rclpy', 'python3-yaml', 'python3-pytest', 'cmake'):
        assert r.resolve(key).satisfied, key


def test_missing_ros_package_uses_the_requirements_pin_before_the_wheel_table():
    r = resolver(pins={'ros-nav-msgs': '9.9.9'}, wheels={'ros-nav-msgs': '5.5.1', 'ros-shape-msgs': '5.5.1'})
    assert r.resolve('nav_msgs').pip == 'ros-nav-msgs==9.9.9'
    assert r.resolve('shape_msgs').pip == 'ros-shape-msgs==5.5.1'


def test_unknown_ros_key_is_unresolvable():
    assert resolver().resolve('turtle_thing').error == 'Cannot locate rosdep definition for [turtle_thing]'


def test_missing_python_key_needs_a_pin():
    r = resolver(pins={'pyyaml': '6.0.3'})
    assert r.resolve('python3-yaml').pip == 'PyYAML==6.0.3'
    error = r.resolve('python3-requests').error
    assert error.startswith('Cannot locate rosdep definition for [python3-requests]')
    assert "'requests'" in error


# Keys a course package plausibly names, and the pinned distribution each one installs.
COURSE_PYTHON_KEYS = {
    'python3-opencv': 'opencv-python', 'python3-pygame': 'pygame', 'python3-numpy': 'numpy',
    'python3-yaml': 'PyYAML', 'python3-pytest': 'pytest', 'python3-setuptools': 'setuptools',
    'python3-pkg-resources': 'setuptools', 'python3-pil': 'pillow',
}


def test_course_python_keys_resolve_to_the_projects_pins_when_missing():
    pins = load_pins(REQUIREMENTS)
    r = resolver(pins=pins)
    for key, distribution in COURSE_PYTHON_KEYS.items():
        assert r.resolve(key).pip == f'{distribution}=={pins[canonicalize_name(distribution)]}', key
    assert 'opencv-python-headless' not in pins  # installed apart by bootstrap.sh, never by rosdep
    # A module requirements.txt does not pin stays an error, as any unknown key.
    assert r.resolve('python3-matplotlib').error.startswith('Cannot locate rosdep definition for '
                                                            '[python3-matplotlib]')


def test_course_python_keys_are_satisfied_by_their_modules():
    r = resolver(modules={'cv2', 'pygame', 'numpy', 'yaml', 'pytest', 'setuptools', 'pkg_resources', 'PIL'})
    for key in COURSE_PYTHON_KEYS:
        assert r.resolve(key).satisfied, key


def test_cv_bridge_is_our_installed_package():
    assert resolver(installed={'cv_bridge'}).resolve('cv_bridge').satisfied
    assert 'cv_bridge' in get_packages_with_prefixes()  # built from src/compat/cv_bridge


def test_missing_tool_is_reported_not_installed():
    assert 'pip cannot install' in resolver().resolve('git').error


def test_plan_installs_each_requirement_once_and_lists_every_error():
    r = resolver(installed={'rclpy'}, wheels={'ros-nav-msgs': '5.5.1'})
    plan = make_plan({'a': ['rclpy', 'nav_msgs', 'nope'], 'b': ['nav_msgs', 'nope', 'other']}, r)
    assert plan.pip == ['ros-nav-msgs==5.5.1']
    assert plan.errors == ['a: Cannot locate rosdep definition for [nope]',
                           'b: Cannot locate rosdep definition for [nope]',
                           'b: Cannot locate rosdep definition for [other]']


def test_plan_looks_each_key_up_once(monkeypatch):
    r = resolver(installed={'rclpy'}, wheels={'ros-nav-msgs': '5.5.1'})
    looked_up = []
    resolve = r.resolve
    monkeypatch.setattr(r, 'resolve', lambda key: looked_up.append(key) or resolve(key))
    make_plan({'a': ['rclpy', 'nav_msgs'], 'b': ['nav_msgs', 'rclpy'], 'c': ['nav_msgs']}, r)
    assert sorted(looked_up) == ['nav_msgs', 'rclpy']


PACKAGE_XML = '''<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.0.0</version>
  <description>d</description>
  <maintainer email="a@b.example">a</maintainer>
  <license>MIT</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <depend>rclpy</depend>
  <exec_depend>std_msgs</exec_depend>
  <exec_depend condition="$ROS_VERSION == 1">rospy</exec_depend>
  <test_depend>python3-pytest</test_depend>
  <doc_depend>doc_tool</doc_depend>
</package>
'''


@pytest.fixture
def workspace(tmp_path, monkeypatch):
    monkeypatch.setitem(os.environ, 'ROS_VERSION', '2')
    for name in ('one', 'two'):
        (tmp_path / name).mkdir()
        (tmp_path / name / 'package.xml').write_text(PACKAGE_XML.format(name=name))
    return tmp_path


def test_dependency_keys_by_type_with_conditions(workspace):
    one = packages_in_paths([str(workspace)])[0]
    assert dependency_keys(one, ['build', 'buildtool', 'build_export', 'buildtool_export', 'exec', 'test',
                                 'doc']) == ['rclpy', 'ament_cmake', 'std_msgs', 'python3-pytest', 'doc_tool']
    assert sorted(dependency_keys(one, ['exec'])) == ['rclpy', 'std_msgs']
    assert dependency_keys(one, ['test']) == ['python3-pytest']


def test_ignored_folders_are_skipped(workspace):
    (workspace / 'two' / 'COLCON_IGNORE').write_text('')
    assert [p.name for p in packages_in_paths([str(workspace)])] == ['one']


def test_bad_paths_and_manifests_raise_one_line(workspace):
    with pytest.raises(ManifestError, match="given path 'nope' does not exist"):
        packages_in_paths(['nope'])
    (workspace / 'two' / 'package.xml').write_text('<package><name>two')
    with pytest.raises(ManifestError) as error:
        packages_in_paths([str(workspace)])
    assert '\n' not in str(error.value)
