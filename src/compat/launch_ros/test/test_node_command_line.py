"""The argv a Node builds, compared with the spec's assembly order (launch.md section 7.2)."""

import os
import re

import pytest
import yaml
from launch import LaunchContext
from launch.actions import GroupAction
from launch.substitutions import LaunchConfiguration, SubstitutionFailure
from launch_ros.actions import Node, PushRosNamespace, SetParameter, SetRemap
from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue
from launch_ros.substitutions import ExecutableInPackage, FindPackageShare

PACKAGE = 'random_number_ps'
EXECUTABLE = 'random_number_publisher'


def executable_path() -> str:
    return ExecutableInPackage(EXECUTABLE, PACKAGE).perform(LaunchContext())


def prepare(node: Node, *scope, configurations: dict | None = None) -> list[str]:
    """Execute the scope actions, then prepare the node as execute() would, without starting it."""
    context = LaunchContext()
    context.launch_configurations.update(configurations or {})
    for action in scope:
        action.visit(context)
    node._expand_names(context)
    node._prepare(context)
    return node.process_description.final_cmd


def params_file(path: str) -> dict:
    assert re.match(r'launch_params_', os.path.basename(path)), path
    with open(path) as handle:
        return yaml.safe_load(handle)


def test_no_name_no_namespace_still_gives_an_empty_ros_args_section():
    argv = prepare(Node(package=PACKAGE, executable=EXECUTABLE))
    assert argv == [executable_path(), '--ros-args']


def test_name_and_relative_namespace():
    node = Node(package=PACKAGE, executable=EXECUTABLE, namespace='turtlesim1', name='sim')
    argv = prepare(node)
    assert argv == [executable_path(), '--ros-args', '-r', '__node:=sim', '-r', '__ns:=/turtlesim1']
    assert re.fullmatch(rf'{EXECUTABLE}-\d+', node.process_description.final_name)
    assert node.node_name == '/turtlesim1/sim'


def test_remappings_follow_the_name_in_order():
    node = Node(package=PACKAGE, executable=EXECUTABLE, name='mimic', remappings=[
        ('/input/pose', '/turtlesim1/turtle1/pose'), ('/output/cmd_vel', '/turtlesim2/turtle1/cmd_vel')])
    assert prepare(node)[1:] == ['--ros-args', '-r', '__node:=mimic',
                                 '-r', '/input/pose:=/turtlesim1/turtle1/pose',
                                 '-r', '/output/cmd_vel:=/turtlesim2/turtle1/cmd_vel']


def test_arguments_and_ros_arguments_come_before_the_generated_section():
    node = Node(package=PACKAGE, executable=EXECUTABLE, arguments=['a', 'b'],
                ros_arguments=['--log-level', 'debug'], name='n')
    assert prepare(node)[1:] == ['a', 'b', '--ros-args', '--log-level', 'debug',
                                 '--ros-args', '-r', '__node:=n']


def test_pushed_namespace_set_parameter_and_set_remap_precede_the_nodes_own():
    node = Node(package=PACKAGE, executable=EXECUTABLE, name='pub', namespace='inner',
                remappings=[('x', 'y')])
    argv = prepare(node, PushRosNamespace('outer'), SetParameter('use_sim_time', True),
                   SetRemap('chatter', 'talk'))
    assert argv[1:] == ['--ros-args', '-r', '__node:=pub', '-r', '__ns:=/outer/inner',
                        '-p', 'use_sim_time:=True', '-r', 'chatter:=talk', '-r', 'x:=y']


def test_absolute_namespace_replaces_the_pushed_one_and_empty_is_root():
    absolute = Node(package=PACKAGE, executable=EXECUTABLE, namespace='/abs')
    assert prepare(absolute, PushRosNamespace('outer'))[-1] == '__ns:=/abs'
    root = Node(package=PACKAGE, executable=EXECUTABLE, namespace='')
    assert prepare(root)[-1] == '__ns:=/'


def test_group_scope_ends_the_pushed_namespace():
    context = LaunchContext()
    group = GroupAction([PushRosNamespace('inside')])
    for entity in group.visit(context):
        entity.visit(context)
    assert 'ros_namespace' not in context.launch_configurations


def test_dict_parameters_go_to_a_temporary_yaml_file_keyed_by_the_full_name():
    node = Node(package=PACKAGE, executable=EXECUTABLE, name='pub', namespace='ns', parameters=[
        {'lower_limit': 5, 'upper_limit': LaunchConfiguration('up'), 'label': 'text',
         'nested': {'ratio': '0.5', 'flag': LaunchConfiguration('flag')}}])
    argv = prepare(node, configurations={'up': '200', 'flag': 'true'})
    assert argv[-2] == '--params-file'
    assert params_file(argv[-1]) == {'/ns/pub': {'ros__parameters': {
        'lower_limit': 5, 'upper_limit': 200, 'label': 'text', 'nested.ratio': '0.5', 'nested.flag': True}}}


def test_dict_parameters_without_a_namespace_use_the_wildcard_key():
    argv = prepare(Node(package=PACKAGE, executable=EXECUTABLE, name='pub', parameters=[{'a': 1.5}]))
    assert params_file(argv[-1]) == {'/**': {'ros__parameters': {'a': 1.5}}}


def test_parameter_files_parameter_objects_and_order(tmp_path):
    existing = tmp_path / 'params.yaml'
    existing.write_text('/**:\n  ros__parameters:\n    lower_limit: 3\n')
    node = Node(package=PACKAGE, executable=EXECUTABLE, parameters=[
        str(existing), {'b': [1, 2.5]}, Parameter('c', 'x y'), ParameterFile(existing),
        {'d': ParameterValue(LaunchConfiguration('num'), value_type=str)}])
    argv = prepare(node, configurations={'num': '42'})
    ros_args = argv[argv.index('--ros-args') + 1:]
    assert ros_args[:2] == ['--params-file', str(existing)]
    assert params_file(ros_args[3]) == {'/**': {'ros__parameters': {'b': [1.0, 2.5]}}}
    assert ros_args[4:6] == ['-p', 'c:=x y']
    assert ros_args[6:8] == ['--params-file', str(existing)]
    assert params_file(ros_args[9]) == {'/**': {'ros__parameters': {'d': '42'}}}


def test_missing_parameter_file_is_skipped(tmp_path, capsys):
    argv = prepare(Node(package=PACKAGE, executable=EXECUTABLE, parameters=[str(tmp_path / 'none.yaml')]))
    assert argv[1:] == ['--ros-args']
    assert 'Parameter file path is not a file:' in capsys.readouterr().out


def test_mixed_type_list_parameter_is_refused():
    node = Node(package=PACKAGE, executable=EXECUTABLE, parameters=[{'bad': [1, 'a']}])
    with pytest.raises(TypeError):
        prepare(node)


@pytest.mark.parametrize(('kwargs', 'error'), [
    ({'name': 'bad name'}, 'Invalid node name'),
    ({'name': '1abc'}, 'Invalid node name'),
    ({'namespace': 'a//b'}, 'Invalid namespace'),
    ({'namespace': '9ns'}, 'Invalid namespace'),
])
def test_invalid_names_are_refused(kwargs, error, capsys):
    with pytest.raises(ValueError, match=error):
        prepare(Node(package=PACKAGE, executable=EXECUTABLE, **kwargs))
    assert 'Error while expanding or validating node name or namespace' in capsys.readouterr().out


def test_wrong_parameter_and_remapping_shapes_are_type_errors():
    with pytest.raises(TypeError):
        Node(package=PACKAGE, executable=EXECUTABLE, parameters={'a': 1})
    with pytest.raises(TypeError, match='tuple of length 2'):
        Node(package=PACKAGE, executable=EXECUTABLE, remappings=[['a', 'b']])


def test_missing_package_and_executable_are_one_line_failures():
    with pytest.raises(SubstitutionFailure, match="package 'no_such_pkg' not found"):
        prepare(Node(package='no_such_pkg', executable='x'))
    with pytest.raises(SubstitutionFailure, match="executable 'nope' not found on the libexec directory"):
        prepare(Node(package=PACKAGE, executable='nope'))


def test_find_package_share():
    share = FindPackageShare(PACKAGE).perform(LaunchContext())
    assert share.endswith(os.path.join('share', PACKAGE))
    assert os.path.isfile(os.path.join(share, 'package.xml'))


def test_upstream_module_paths_used_by_launch_files():
    from launch.some_substitutions_type import SomeSubstitutionsType
    from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions
    from launch_ros.descriptions import ParameterValue as DescribedValue

    assert DescribedValue is ParameterValue
    assert SomeSubstitutionsType is not None
    context = LaunchContext()
    assert perform_substitutions(context, normalize_to_list_of_substitutions(['a', 'b'])) == 'ab'
