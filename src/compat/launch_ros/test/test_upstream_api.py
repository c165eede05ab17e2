"""launch_ros as upstream documents it, checked on ours.

Module paths, $(param), SetUseSimTime, SetROSLogDir, the lifecycle pieces' checks, and what is refused
(composition, bare parameter values).
"""

import importlib
import os

import lifecycle_msgs.msg
import pytest
from launch import LaunchContext, LaunchDescription, LaunchService
from launch.actions import GroupAction, LogInfo
from launch.frontend import LaunchFileError, Parser
from launch.substitutions import SubstitutionFailure
from launch_ros.actions import (
    ComposableNodeContainer,
    LifecycleNode,
    LifecycleTransition,
    Node,
    SetParameter,
    SetROSLogDir,
    SetUseSimTime,
)
from launch_ros.actions.composable_node_container import CompositionUnavailableError
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState
from launch_ros.substitutions import Parameter

pytestmark = pytest.mark.usefixtures('isolated_launch')


UPSTREAM_PATHS = {
    'launch_ros.utilities': 'make_namespace_absolute',
    'launch_ros.utilities.evaluate_parameters': 'evaluate_parameters',
    'launch_ros.utilities.namespace_utils': 'prefix_namespace',
    'launch_ros.utilities.normalize_parameters': 'normalize_parameters',
    'launch_ros.utilities.normalize_remap_rule': 'normalize_remap_rules',
    'launch_ros.utilities.track_node_names': 'add_node_name',
    'launch_ros.events.lifecycle': 'ChangeState',
    'launch_ros.events.lifecycle.change_state': 'ChangeState',
    'launch_ros.events.lifecycle.lifecycle_node_matchers': 'matches_node_name',
    'launch_ros.events.lifecycle.state_transition': 'StateTransition',
    'launch_ros.events.matchers': 'matches_node_name',
    'launch_ros.events.matchers.matches_node_name': 'matches_node_name',
    'launch_ros.event_handlers.on_state_transition': 'OnStateTransition',
    'launch_ros.actions.composable_node_container': 'ComposableNodeContainer',
    'launch_ros.actions.lifecycle_node': 'LifecycleNode',
    'launch_ros.actions.lifecycle_transition': 'LifecycleTransition',
    'launch_ros.actions.load_composable_nodes': 'LoadComposableNodes',
    'launch_ros.actions.node': 'Node',
    'launch_ros.actions.ros_timer': 'ROSTimer',
    'launch_ros.actions.set_parameter': 'SetParameter',
    'launch_ros.actions.set_parameters_from_file': 'SetParametersFromFile',
    'launch_ros.actions.set_remap': 'SetRemap',
    'launch_ros.actions.push_ros_namespace': 'PushROSNamespace',
    'launch_ros.actions.set_use_sim_time': 'SetUseSimTime',
    'launch_ros.actions.set_ros_log_dir': 'SetROSLogDir',
    'launch_ros.substitutions.executable_in_package': 'ExecutableInPackage',
    'launch_ros.substitutions.parameter': 'Parameter',
    'launch_ros.substitutions.find_package': 'FindPackageShare',
    'launch_ros.descriptions': 'ParameterValue',
    'launch_ros.descriptions.composable_node': 'ComposableNode',
    'launch_ros.parameter_descriptions': 'ParameterFile',
    'launch_ros.parameters_type': 'SomeParameters',
    'launch_ros.remap_rule_type': 'SomeRemapRules',
    'launch_ros.ros_adapters': 'get_ros_node',
}


def run(*entities) -> int:
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription(list(entities)))
    return service.run()


def user_lines(capsys) -> list[str]:
    return [line.split(': ', 1)[1] for line in capsys.readouterr().out.splitlines()
            if line.startswith('[INFO] [launch.user]')]


@pytest.mark.parametrize('module', UPSTREAM_PATHS)
def test_upstream_module_paths(module):
    assert getattr(importlib.import_module(module), UPSTREAM_PATHS[module])


# The modules whose name their subpackage exports too (launch_ros.events exports the module lifecycle).
IN_SUBPACKAGE = [m for m in UPSTREAM_PATHS
                 if m.rsplit('.', 1)[0] != 'launch_ros' and m != 'launch_ros.events.lifecycle']


@pytest.mark.parametrize('module', IN_SUBPACKAGE)
def test_a_module_path_gives_the_object_its_package_exports(module):
    name = UPSTREAM_PATHS[module]
    package = importlib.import_module(module.rsplit('.', 1)[0])
    assert getattr(importlib.import_module(module), name) is getattr(package, name)


def test_param_substitution_reads_the_latest_set_parameter_in_scope(capsys):
    assert run(
        SetParameter('rate', 5), SetParameter('mode', 'fast'),
        GroupAction([SetParameter('mode', 'slow'), LogInfo(msg=[Parameter('mode'), ' ', Parameter('rate')])]),
        LogInfo(msg=Parameter('mode')),
    ) == 0
    assert user_lines(capsys) == ['slow 5', 'fast']


def test_param_in_xml(tmp_path, capsys):
    path = tmp_path / 'p.launch.xml'
    path.write_text('<launch><set_parameter name="robot" value="owl"/>'
                    '<log message="robot is $(param robot)"/></launch>')
    root, parser = Parser.load(path)
    assert run(parser.parse_description(root)) == 0
    assert user_lines(capsys) == ['robot is owl']


def test_param_that_was_never_set_is_a_substitution_failure():
    with pytest.raises(SubstitutionFailure, match="parameter 'nope' not found"):
        Parameter('nope').perform(LaunchContext())


def test_param_with_three_arguments_is_refused(tmp_path):
    path = tmp_path / 'p.launch.xml'
    path.write_text('<launch><log message="$(param a b c)"/></launch>')
    root, parser = Parser.load(path)
    with pytest.raises(LaunchFileError, match="'param' expects 1 to 2 argument"):
        parser.parse_description(root)


def test_set_use_sim_time_gives_every_later_node_the_parameter(tmp_path):
    path = tmp_path / 's.launch.xml'
    path.write_text('<launch><set_use_sim_time value="True"/></launch>')
    root, parser = Parser.load(path)
    context = LaunchContext()
    for action in parser.parse_description(root).entities:
        action.visit(context)
    assert context.launch_configurations['global_params'] == [('use_sim_time', True)]


def test_set_use_sim_time_refuses_anything_but_true_or_false():
    with pytest.raises(ValueError, match="must be 'true' or 'false', got 'yes please'"):
        SetUseSimTime('yes please').visit(LaunchContext())


def test_set_ros_log_dir_joins_a_relative_directory_under_the_current_one(tmp_path):
    context = LaunchContext()
    SetROSLogDir('robot').visit(context)
    SetROSLogDir('arm').visit(context)
    assert os.environ['ROS_LOG_DIR'] == str(tmp_path / 'log' / 'robot' / 'arm')
    SetROSLogDir('/abs/logs').visit(context)
    assert os.environ['ROS_LOG_DIR'] == '/abs/logs'
    with pytest.raises(ValueError, match='needs a directory'):
        SetROSLogDir('').visit(context)


def test_set_ros_log_dir_in_a_group_does_not_leak(tmp_path, capsys):
    from launch.substitutions import EnvironmentVariable

    assert run(GroupAction([SetROSLogDir('inner'), LogInfo(msg=EnvironmentVariable('ROS_LOG_DIR'))]),
               LogInfo(msg=EnvironmentVariable('ROS_LOG_DIR'))) == 0
    assert user_lines(capsys) == [str(tmp_path / 'log' / 'inner'), str(tmp_path / 'log')]


def test_composable_node_container_refuses_in_one_line(tmp_path):
    with pytest.raises(CompositionUnavailableError) as error:
        ComposableNodeContainer(name='c', namespace='', package='rclcpp_components',
                                executable='component_container')
    assert '\n' not in str(error.value)
    assert 'rclcpp_components' in str(error.value)
    path = tmp_path / 'c.launch.xml'
    path.write_text('<launch><node_container pkg="p" exec="e" name="c" namespace=""/></launch>')
    root, parser = Parser.load(path)
    with pytest.raises(LaunchFileError, match='<node_container> is not available here'):
        parser.parse_description(root)


@pytest.mark.parametrize('bad', [5.0, 3, True, None])
def test_node_refuses_a_bare_parameter_value(bad):
    with pytest.raises(TypeError, match='Node parameters must be dicts'):
        Node(package='p', executable='e', parameters=[bad])


def test_lifecycle_node_needs_a_name():
    with pytest.raises(TypeError, match="LifecycleNode requires 'name'"):
        LifecycleNode(package='p', executable='e')
    assert LifecycleNode(package='p', executable='e', name='n', autostart=True).node_autostart is True


def test_change_state_refuses_an_unknown_transition():
    with pytest.raises(ValueError, match='unknown lifecycle transition id 42'):
        ChangeState(lifecycle_node_matcher=lambda action: True, transition_id=42)


def test_lifecycle_transition_checks_its_lists():
    with pytest.raises(ValueError, match='No transition_ids'):
        LifecycleTransition(lifecycle_node_names=['n'], transition_ids=[])
    with pytest.raises(TypeError, match='expects lists'):
        LifecycleTransition(lifecycle_node_names='n', transition_ids=[1])
    with pytest.raises(ValueError, match="integer lifecycle transition id, got 'go'"):
        LifecycleTransition(lifecycle_node_names=['n'], transition_ids=['go']).visit(LaunchContext())


def test_lifecycle_transition_requests_the_first_transition_of_each_node():
    action = LifecycleTransition(lifecycle_node_names=['a', '/b'],
                                 transition_ids=[lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE,
                                                 lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE])
    emitted = [entity.event for entity in action.visit(LaunchContext()) if hasattr(entity, 'event')]
    configure = lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE
    assert [event.transition_id for event in emitted] == [configure] * 2

    class Named:
        def __init__(self, name):
            self.node_name = name
    assert [event.lifecycle_node_matcher(Named('/a')) for event in emitted] == [True, False]


def test_on_state_transition_needs_a_lifecycle_node_target():
    with pytest.raises(TypeError, match='requires a LifecycleNode'):
        OnStateTransition(target_lifecycle_node=Node(package='p', executable='e'), entities=[])
