"""ros2pkg.api.create and ros2pkg.templates as plain functions: checks, plan order, file contents."""

import ast
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest
from catkin_pkg.package import parse_package_string
from ros2pkg.api.create import (
    CreateError,
    check_build_type,
    check_license,
    check_package_name,
    check_settings,
    closest,
    default_email,
    plan,
    summary,
    write_package,
)
from ros2pkg.templates import LICENSES, PackageSettings, cmakelists, package_xml, setup_py


def settings(tmp_path, **overrides):
    values = dict(name='my_pkg', build_type='ament_python', dependencies=[], description='d',
                  license_name='TODO: License declaration', maintainer_name='Ann',
                  maintainer_email=None, node_name=None, library_name=None, package_format=3,
                  destination=str(tmp_path), warn=lambda line: None)
    values.update(overrides)
    return check_settings(**values)


@pytest.mark.parametrize(('typed', 'meant'), [
    ('ament-python', 'ament_python'), ('AMENT_CMAKE', 'ament_cmake'), ('ament_pyhton', 'ament_python'),
    ('amentpython', 'ament_python')])
def test_build_type_typos_get_a_suggestion(typed, meant):
    with pytest.raises(CreateError) as error:
        check_build_type(typed)
    assert str(error.value) == f"unknown build type '{typed}', did you mean '{meant}'?"
    assert error.value.exit_code == 2


def test_unrelated_build_type_lists_the_choices():
    with pytest.raises(CreateError, match=r"unknown build type 'scons', choose from 'ament_cmake', "
                                          r"'ament_python'"):
        check_build_type('scons')


def test_upstream_build_types_this_environment_cannot_build_are_refused_clearly():
    with pytest.raises(CreateError, match="build type 'cmake' is not supported here"):
        check_build_type('cmake')


@pytest.mark.parametrize(('name', 'suggestion'), [
    ('My-Package', 'my_package'), ('olive__launch', 'olive_launch'), ('2fast', ''), ('a b', 'a_b'),
    ('Turtle', 'turtle')])
def test_invalid_package_names_are_refused_with_a_rep144_suggestion(name, suggestion):
    with pytest.raises(CreateError) as error:
        check_package_name(name)
    message = str(error.value)
    assert message.startswith(f"invalid package name '{name}'")
    assert 'REP 144' in message
    assert (f"did you mean '{suggestion}'?" in message) == bool(suggestion)


def test_valid_package_names_pass():
    for name in ('random_number_ps', 'olive_interfaces', 'a1', 'x'):
        assert check_package_name(name) is None, name  # no CreateError


def test_licenses_known_free_text_and_near_misses():
    assert check_license('Apache-2.0') is True
    assert check_license('TODO: License declaration') is False
    assert check_license('Proprietary') is False
    for near_miss, meant in (('apache-2.0', 'Apache-2.0'), ('MIT License', 'MIT'), ('BSD-3', 'BSD-3-Clause')):
        with pytest.raises(CreateError, match=f"unknown license '{near_miss}', did you mean '{meant}'"):
            check_license(near_miss)


def test_default_email_is_valid_for_any_maintainer_name():
    assert default_email('Nobody Here') == 'Nobody_Here@todo.todo'
    assert default_email('???') == 'user@todo.todo'


def test_closest_ignores_case_and_dashes():
    assert closest('Ament-Cmake', ('ament_cmake', 'ament_python')) == 'ament_cmake'
    assert closest('zzz', ('ament_cmake',)) is None


@pytest.mark.parametrize(('field', 'value', 'expected'), [
    ('dependencies', ['rclpy', 'bad dep'], "invalid dependency 'bad dep'"),
    ('maintainer_email', 'not-an-email', "invalid maintainer email 'not-an-email'"),
    ('maintainer_email', 'a@b', "invalid maintainer email 'a@b'"),
    ('description', ' ', 'the description must not be empty'),
    ('license_name', '', 'the license must not be empty'),
    ('maintainer_name', '  ', 'the maintainer name must not be empty'),
    ('node_name', 'my-node', "invalid node name 'my-node'"),
    ('node_name', 'class', "invalid node name 'class'"),
    ('library_name', '9lib', "invalid library name '9lib'"),
])
def test_bad_values_are_refused_in_one_line(tmp_path, field, value, expected):
    with pytest.raises(CreateError) as error:
        settings(tmp_path, **{field: value})
    assert str(error.value).startswith(expected)
    assert '\n' not in str(error.value)


def test_existing_directory_and_file_destination_are_refused(tmp_path):
    (tmp_path / 'my_pkg').mkdir()
    with pytest.raises(CreateError, match='The directory already exists'):
        settings(tmp_path)
    a_file = tmp_path / 'file'
    a_file.write_text('')
    with pytest.raises(CreateError, match='the destination is not a directory'):
        settings(tmp_path, destination=str(a_file))


def test_python_package_named_test_is_refused(tmp_path):
    with pytest.raises(CreateError, match="'ament_python' packages can't be named 'test'"):
        settings(tmp_path, name='test')


def test_node_named_like_the_library_is_renamed_with_warnings(tmp_path):
    warnings = []
    p = settings(tmp_path, build_type='ament_cmake', node_name='core', library_name='core',
                 warn=warnings.append)
    assert p.node_name == 'core_node'
    assert warnings == ['[WARNING] node name can not be equal to the library name',
                        '[WARNING] renaming node to core_node']


def test_python_plan_follows_upstream_order(tmp_path):
    p = settings(tmp_path, node_name='talker', license_name='MIT')
    root = os.path.join(str(tmp_path), 'my_pkg')
    messages = [step.message for step in plan(p, str(tmp_path)) if step.message]
    assert messages == [
        f'creating folder {root}', f'creating {root}/package.xml', 'creating source folder',
        f'creating folder {root}/my_pkg', f'creating {root}/setup.py', f'creating {root}/setup.cfg',
        f'creating folder {root}/resource', f'creating {root}/resource/my_pkg',
        f'creating {root}/my_pkg/__init__.py', f'creating folder {root}/test',
        f'creating {root}/test/test_copyright.py', f'creating {root}/test/test_flake8.py',
        f'creating {root}/test/test_pep257.py',
        f'creating {root}/my_pkg/talker.py']
    assert plan(p, str(tmp_path))[-1].path == f'{root}/LICENSE'  # written silently


def test_summary_lines_match_upstream(tmp_path):
    p = settings(tmp_path, maintainer_email='ann@example.com', dependencies=['rclpy'], node_name='n')
    assert summary(p, str(tmp_path)) == [
        'going to create a new package', 'package name: my_pkg',
        f'destination directory: {tmp_path}', 'package format: 3', 'version: 0.0.0', 'description: d',
        "maintainer: ['Ann <ann@example.com>']", "licenses: ['TODO: License declaration']",
        'build type: ament_python', "dependencies: ['rclpy']", 'node_name: n']


def test_package_xml_parses_with_escaped_text():
    p = PackageSettings(name='p', build_type='ament_python', description='a < b & "c"',
                        maintainer_name='A & B', maintainer_email='a@b.example', dependencies=['rclpy'])
    package = parse_package_string(package_xml(p))
    assert package.name == 'p'
    assert ET.fromstring(package_xml(p)).findtext('description') == 'a < b & "c"'
    assert [str(d) for d in package.build_depends] == ['rclpy']
    assert package.maintainers[0].name == 'A & B'
    assert package.get_build_type() == 'ament_python'


def test_setup_py_is_valid_python_even_with_quotes_in_values():
    p = PackageSettings(name='p', build_type='ament_python', description="it's \"quoted\"",
                        node_name='n')
    tree = ast.parse(setup_py(p))
    assert "            'n = p.n:main'\n        ],\n" in setup_py(p)  # upstream's: no trailing comma
    assert tree.body


def test_cmakelists_declares_dependencies_node_library_and_tests():
    p = PackageSettings(name='p', dependencies=['std_msgs'], node_name='n', library_name='lib')
    text = cmakelists(p)
    for expected in ('project(p)', 'find_package(std_msgs REQUIRED)', 'add_executable(n src/n.cpp)',
                     'add_library(lib src/lib.cpp)', 'target_link_libraries(n lib ${std_msgs_TARGETS})',
                     'ament_add_test(n_runs', 'PASS_REGULAR_EXPRESSION "hello world p package"',
                     'ament_export_targets(export_${PROJECT_NAME})', 'ament_package()',
                     'find_package(ament_cmake REQUIRED)\nfind_package(ament_cmake_ros REQUIRED)\n'):
        assert expected in text
    assert text.count('(') == text.count(')')


def test_license_list_is_upstreams():
    assert LICENSES[0] == 'Apache-2.0'
    assert 'LGPL-3.0-only' in LICENSES
    assert len(LICENSES) == 9


def test_python_library_is_a_subpackage(tmp_path):
    p = settings(tmp_path, library_name='helpers')
    root = os.path.join(str(tmp_path), 'my_pkg')
    steps = plan(p, str(tmp_path))
    assert [step.message for step in steps[-2:]] == [f'creating folder {root}/my_pkg/helpers',
                                                      f'creating {root}/my_pkg/helpers/__init__.py']


def test_package_format_2_is_declared(tmp_path):
    text = package_xml(settings(tmp_path, package_format=2))
    assert '<package format="2">' in text
    assert 'package_format2.xsd' in text
    assert parse_package_string(text).package_format == 2


def written_python_package(tmp_path, **overrides):
    p = settings(tmp_path, **overrides)
    write_package(plan(p, str(tmp_path)), say=lambda line: None)
    return tmp_path / p.name


def decorators_and_calls(source):
    """{test function: (its decorators, the linter call in it)} of a generated test file."""
    tree = ast.parse(source)
    return {node.name: ([ast.unparse(d) for d in node.decorator_list], ast.unparse(node.body[0].value))
            for node in tree.body if isinstance(node, ast.FunctionDef)}


def test_python_packages_get_upstreams_linter_tests_and_test_depends(tmp_path):
    package = written_python_package(tmp_path)
    tests = {path.name: path.read_text() for path in (package / 'test').iterdir()}
    assert sorted(tests) == ['test_copyright.py', 'test_flake8.py', 'test_pep257.py']
    assert tests['test_copyright.py'].startswith('from ament_copyright.main import main\nimport pytest\n')
    assert decorators_and_calls(tests['test_copyright.py']) == {'test_copyright': (
        ["pytest.mark.skip(reason='No copyright header has been placed in the generated source file.')",
         'pytest.mark.copyright', 'pytest.mark.linter'], "main(argv=['.', 'test'])")}
    assert tests['test_flake8.py'].startswith(
        'from ament_flake8.main import main_with_errors\nimport pytest\n')
    assert decorators_and_calls(tests['test_flake8.py']) == {'test_flake8': (
        ['pytest.mark.flake8', 'pytest.mark.linter'], 'main_with_errors(argv=[])')}
    assert tests['test_pep257.py'].startswith('from ament_pep257.main import main\nimport pytest\n')
    assert decorators_and_calls(tests['test_pep257.py']) == {'test_pep257': (
        ['pytest.mark.linter', 'pytest.mark.pep257'], "main(argv=['.', 'test'])")}
    manifest = parse_package_string((package / 'package.xml').read_text())
    assert [str(d) for d in manifest.test_depends] == [
        'ament_copyright', 'ament_flake8', 'ament_pep257', 'python3-pytest']


def run_package_tests(package):
    return subprocess.run([sys.executable, '-m', 'pytest', '-p', 'no:cacheprovider', '-q'],
                          cwd=package, capture_output=True, text=True, timeout=120)


def test_a_fresh_python_package_passes_its_linter_tests_and_they_catch_problems(tmp_path):
    package = written_python_package(tmp_path, node_name='talker', license_name='MIT')
    fresh = run_package_tests(package)
    assert fresh.returncode == 0, fresh.stdout + fresh.stderr
    assert '2 passed, 1 skipped' in fresh.stdout
    (package / 'my_pkg' / 'talker.py').write_text('import os\n\n\ndef main():\n    """Greet."""\n')
    broken = run_package_tests(package)
    assert broken.returncode == 1
    assert 'F401' in broken.stdout
    assert '1 failed, 1 passed, 1 skipped' in broken.stdout  # flake8's test fails, pep257's passes


def test_cmake_libraries_build_with_ament_cmake_ros_as_upstream(tmp_path):
    def buildtool_depends(p):
        return [str(d) for d in parse_package_string(package_xml(p)).buildtool_depends]

    library = settings(tmp_path, build_type='ament_cmake', library_name='lib')
    assert buildtool_depends(library) == ['ament_cmake_ros']
    node_only = settings(tmp_path, build_type='ament_cmake', node_name='n')
    assert buildtool_depends(node_only) == ['ament_cmake']
    assert 'ament_cmake_ros' not in cmakelists(node_only)
