"""`ros2 pkg`: the installed command against the installed workspace, and a fresh package built end to end."""

import argparse
import os
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from ros2pkg.command.pkg import PkgCommand

TIMEOUT = 60


def ros2(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(['ros2', *args], capture_output=True, text=True, cwd=cwd, timeout=TIMEOUT)


def in_workspace(workspace: Path, command: str, timeout: float = 300) -> subprocess.CompletedProcess:
    """A shell command in the workspace, with its install/ overlay sourced when it exists."""
    setup = workspace / 'install' / 'local_setup.bash'
    script = (f'source {setup} && ' if setup.exists() else '') + command
    return subprocess.run(['bash', '-c', script], capture_output=True, text=True, cwd=workspace,
                          timeout=timeout)


def assert_one_line_error(result: subprocess.CompletedProcess, code: int, text: str) -> None:
    assert result.returncode == code, result.stdout + result.stderr
    assert 'Traceback' not in result.stderr
    assert result.stderr.strip().splitlines() == [result.stderr.strip()], result.stderr
    assert text in result.stderr


def test_list_is_sorted_and_has_the_workspace_and_the_underlay():
    result = ros2('pkg', 'list')
    assert result.returncode == 0, result.stderr
    names = result.stdout.split()
    assert {'ros2cli', 'ros2pkg', 'rclpy', 'std_msgs', 'random_number_ps'} <= set(names)
    assert names == sorted(names)


def test_prefix_and_share():
    prefix = ros2('pkg', 'prefix', 'ros2cli')
    assert prefix.returncode == 0
    lines = prefix.stdout.splitlines()
    assert len(lines) == 1
    assert Path(lines[0]).is_dir()
    share = ros2('pkg', 'prefix', '--share', 'ros2cli')
    assert share.stdout.strip() == str(Path(lines[0]) / 'share' / 'ros2cli')


@pytest.mark.parametrize('name', ['not_a_package', 'invalid.package.name', 'a/b'])
def test_prefix_of_unknown_package(name):
    assert_one_line_error(ros2('pkg', 'prefix', name), 1, 'Package not found')


def test_xml_prints_the_manifest_and_single_tags():
    result = ros2('pkg', 'xml', 'ros2cli')
    assert result.returncode == 0
    root = ET.fromstring(result.stdout)
    assert root.tag == 'package'
    assert root.findtext('name') == 'ros2cli'
    tag = ros2('pkg', 'xml', 'ros2pkg', '-t', 'exec_depend')
    assert tag.stdout.splitlines() == ['ros2cli', 'ament_index_python']


@pytest.mark.parametrize(('args', 'message'), [
    (['not_a_package'], 'Package not found'),
    (['ros2cli', '-t', 'not_a_tag'], 'XML tag not found'),
    (['ros2cli', '--tag', '['], 'XML tag not found'),
])
def test_xml_bad_input(args, message):
    assert_one_line_error(ros2('pkg', 'xml', *args), 1, message)


def test_executables_of_one_package_and_of_all():
    one = ros2('pkg', 'executables', 'random_number_ps')
    assert one.returncode == 0
    assert 'random_number_ps random_number_publisher' in one.stdout.splitlines()
    assert one.stdout.splitlines() == sorted(one.stdout.splitlines())
    full = ros2('pkg', 'executables', 'random_number_ps', '--full-path')
    assert all(os.access(path, os.X_OK) for path in full.stdout.split())
    assert one.stdout.splitlines()[0] in ros2('pkg', 'executables').stdout.splitlines()


def test_executables_of_unknown_package():
    assert_one_line_error(ros2('pkg', 'executables', 'nope'), 1, "Package 'nope' not found")


def test_create_prints_upstreams_lines_and_writes_the_files(tmp_path):
    result = ros2('pkg', 'create', 'a_test_package', '--package-format', '3',
                  '--description', 'A test package dummy description', '--license', 'Apache-2.0',
                  '--build-type', 'ament_cmake', '--dependencies', 'ros2pkg',
                  '--maintainer-email', 'nobody@nowhere.com', '--maintainer-name', 'Nobody',
                  '--node-name', 'test_node', '--library-name', 'test_library', cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    p = './a_test_package'
    assert result.stdout.splitlines() == [
        'going to create a new package', 'package name: a_test_package',
        f'destination directory: {tmp_path}', 'package format: 3', 'version: 0.0.0',
        'description: A test package dummy description', "maintainer: ['Nobody <nobody@nowhere.com>']",
        "licenses: ['Apache-2.0']", 'build type: ament_cmake', "dependencies: ['ros2pkg']",
        'node_name: test_node', 'library_name: test_library', f'creating folder {p}',
        f'creating {p}/package.xml', 'creating source and include folder', f'creating folder {p}/src',
        f'creating folder {p}/include/a_test_package', f'creating {p}/CMakeLists.txt',
        f'creating {p}/src/test_node.cpp', f'creating {p}/include/a_test_package/test_library.hpp',
        f'creating {p}/src/test_library.cpp', f'creating {p}/include/a_test_package/visibility_control.h']
    package = tmp_path / 'a_test_package'
    assert (package / 'LICENSE').read_text().startswith('SPDX-License-Identifier: Apache-2.0')
    root = ET.parse(package / 'package.xml').getroot()
    assert root.get('format') == '3'
    assert root.findtext('name') == 'a_test_package'
    maintainer = root.find('maintainer')
    assert maintainer is not None
    assert maintainer.text == 'Nobody'
    assert maintainer.get('email') == 'nobody@nowhere.com'
    assert root.findtext('license') == 'Apache-2.0'
    assert root.findtext('depend') == 'ros2pkg'
    assert root.findtext('export/build_type') == 'ament_cmake'


def test_create_with_an_unknown_license_warns_like_upstream(tmp_path):
    result = ros2('pkg', 'create', 'p', '--build-type', 'ament_python', cwd=tmp_path)
    assert result.returncode == 0
    assert ("[WARNING]: Unknown license 'TODO: License declaration'.  This has been set in the "
            'package.xml, but no LICENSE file has been created.') in result.stdout
    assert not (tmp_path / 'p' / 'LICENSE').exists()


def test_license_question_mark_lists_the_supported_licenses(tmp_path):
    result = ros2('pkg', 'create', 'p', '--license', '?', cwd=tmp_path)
    assert result.returncode == 0
    assert result.stdout.splitlines()[:3] == ['Supported licenses:', 'Apache-2.0', 'BSL-1.0']
    assert not (tmp_path / 'p').exists()


@pytest.mark.parametrize(('args', 'code', 'message'), [
    (['olive_srvcli', '--build-type', 'ament-python'], 2, "did you mean 'ament_python'?"),
    (['olive_srvcli', '--build-type', 'ament_cpp'], 2, "did you mean 'ament_cmake'?"),
    (['Bad-Name'], 1, "invalid package name 'Bad-Name'"),
    (['olive__launch'], 1, "did you mean 'olive_launch'?"),
    (['test', '--build-type', 'ament_python'], 1, "packages can't be named 'test'"),
    (['p', '--license', 'apache-2.0'], 1, "did you mean 'Apache-2.0'?"),
    (['p', '--maintainer-email', 'nobody'], 1, "invalid maintainer email 'nobody'"),
    (['p', '--node-name', 'my-node'], 1, "invalid node name 'my-node'"),
    (['p', '--library-name', 'lib.x'], 1, "invalid library name 'lib.x'"),
    (['p', '--dependencies', 'rclpy', 'std msgs'], 1, "invalid dependency 'std msgs'"),
    (['p', '--description', ''], 1, 'the description must not be empty'),
    (['p', '--destination-directory', 'a_file'], 1, 'the destination is not a directory'),
    (['existing'], 1, 'The directory already exists: ./existing'),
])
def test_create_bad_input_one_line_and_nothing_written(tmp_path, args, code, message):
    (tmp_path / 'a_file').write_text('')
    (tmp_path / 'existing').mkdir()
    before = sorted(tmp_path.iterdir())
    assert_one_line_error(ros2('pkg', 'create', *args, cwd=tmp_path), code, message)
    assert sorted(tmp_path.iterdir()) == before


@pytest.mark.parametrize('args', [[], ['p', '--package-format', '4']])
def test_create_usage_errors_exit_2(tmp_path, args):
    result = ros2('pkg', 'create', *args, cwd=tmp_path)
    assert result.returncode == 2
    assert 'ros2 pkg create: error:' in result.stderr
    assert 'Traceback' not in result.stderr


def test_created_packages_build_run_and_pass_their_tests(tmp_path):
    src = tmp_path / 'src'
    src.mkdir()
    for args in (['py_pkg', '--build-type', 'ament_python', '--dependencies', 'rclpy', 'std_msgs',
                  '--node-name', 'py_node', '--license', 'MIT'],
                 ['cpp_pkg', '--build-type', 'ament_cmake', '--dependencies', 'std_msgs',
                  '--node-name', 'cpp_node', '--library-name', 'cpp_lib']):
        assert ros2('pkg', 'create', *args, cwd=src).returncode == 0
    build = in_workspace(tmp_path, 'colcon build')
    assert build.returncode == 0, build.stdout + build.stderr
    run_py = in_workspace(tmp_path, 'ros2 run py_pkg py_node', timeout=TIMEOUT)
    assert run_py.stdout == 'Hi from py_pkg.\n', run_py.stderr
    run_cpp = in_workspace(tmp_path, 'ros2 run cpp_pkg cpp_node', timeout=TIMEOUT)
    assert run_cpp.stdout == 'hello world cpp_pkg package\n', run_cpp.stderr
    listed = in_workspace(tmp_path, 'ros2 pkg executables py_pkg', timeout=TIMEOUT)
    assert listed.stdout == 'py_pkg py_node\n'
    test = in_workspace(tmp_path, 'colcon test --return-code-on-test-failure')
    assert test.returncode == 0, test.stdout + test.stderr
    results = in_workspace(tmp_path, 'colcon test-result --all')
    assert results.returncode == 0, results.stdout
    # py_pkg: upstream's copyright (skipped until the files carry headers), flake8 and pep257 tests.
    assert 'py_pkg/pytest.xml: 3 tests, 0 errors, 0 failures, 1 skipped' in results.stdout
    assert 'Summary: 7 tests, 0 errors, 0 failures, 1 skipped' in results.stdout


def test_pkg_without_a_verb_prints_its_help():
    result = ros2('pkg')
    assert result.returncode == 0
    for verb in ('create', 'executables', 'list', 'prefix', 'xml'):
        assert f'\n  {verb} ' in result.stdout


def test_shell_completion_offers_package_names_build_types_and_licenses(monkeypatch):
    import ros2cli.command

    def verb_parser(verb):
        """The sub-parser of `ros2 pkg <verb>` as shell completion builds it (only that verb's options)."""
        monkeypatch.setattr(ros2cli.command, 'ARGV', ['pkg', verb])
        parser = argparse.ArgumentParser(prog='ros2 pkg')
        PkgCommand().add_arguments(parser, 'ros2 pkg')
        verbs = next(action for action in parser._actions if isinstance(action, argparse._SubParsersAction))
        return verbs.choices[verb]

    completers = {option: action.completer for action in verb_parser('create')._actions
                  for option in action.option_strings if hasattr(action, 'completer')}
    assert completers['--build-type']() == ['ament_cmake', 'ament_python']
    assert 'Apache-2.0' in completers['--license']()
    prefix_package = next(action for action in verb_parser('prefix')._actions
                          if action.dest == 'package_name')
    assert 'ros2cli' in prefix_package.completer()
