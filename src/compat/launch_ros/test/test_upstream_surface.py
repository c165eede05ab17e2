"""The parts of upstream Jazzy's launch_ros surface a review found missing, checked one behaviour each.

utilities (namespaces, parameter normalising/evaluating, rclpy parameter lists, plugin versions), the
load-request helper of composition, `$(param name default)`, Node's name members and extensions.
"""

import os
import pathlib
import types

import lifecycle_msgs.msg
import pytest
import rclpy.parameter
from launch import LaunchContext, LaunchDescription, LaunchService
from launch.actions import LogInfo
from launch.frontend import Parser
from launch.substitutions import SubstitutionFailure, TextSubstitution
from launch.utilities import perform_substitutions
from launch_ros.actions import LifecycleNode, Node, PushRosNamespace, SetParameter
from launch_ros.actions import node as node_module
from launch_ros.actions.lifecycle_transition import match_node_name_goal, match_node_name_start_goal
from launch_ros.actions.load_composable_nodes import get_composable_node_load_request
from launch_ros.descriptions.composable_node import CompositionUnavailableError
from launch_ros.events.lifecycle import StateTransition
from launch_ros.parameter_descriptions import Parameter as ParameterDescription
from launch_ros.parameter_descriptions import ParameterFile, ParameterValue
from launch_ros.ros_adapters import ROSAdapter
from launch_ros.substitutions import Parameter
from launch_ros.utilities import (
    evaluate_parameters,
    is_namespace_absolute,
    is_root_namespace,
    make_namespace_absolute,
    normalize_parameters,
    normalize_remap_rule,
    normalize_remap_rules,
    prefix_namespace,
    to_parameters_list,
)
from launch_ros.utilities.plugin_support import (
    PluginException,
    get_upper_bound_caret_version,
    satisfies_version,
)
from packaging.version import Version

pytestmark = pytest.mark.usefixtures('isolated_launch')


def prepare(node: Node, *scope) -> list[str]:
    """Run the scope actions, then build the node's command line as execute() would, starting nothing."""
    context = LaunchContext()
    for action in scope:
        action.visit(context)
    node._expand_names(context)
    node._prepare(context)
    return node.process_description.final_cmd


def evaluated(*parameters):
    return evaluate_parameters(LaunchContext(), normalize_parameters(list(parameters)))


# ---- launch_ros.utilities ----

def test_utilities_export_upstreams_names():
    import launch_ros.utilities as utilities

    for name in ('add_node_name', 'evaluate_parameters', 'get_node_name_count', 'is_namespace_absolute',
                 'is_root_namespace', 'make_namespace_absolute', 'normalize_parameters',
                 'normalize_remap_rule', 'normalize_remap_rules', 'prefix_namespace', 'to_parameters_list'):
        assert name in utilities.__all__, name
        assert callable(getattr(utilities, name)), name
    from launch_ros.utilities import plugin_support  # a submodule, as upstream's Node imports it

    assert plugin_support.PluginException is PluginException


def test_namespace_predicates():
    assert is_namespace_absolute('/a')
    assert not is_namespace_absolute('a')
    assert is_root_namespace('/')
    assert not is_root_namespace('')
    assert not is_root_namespace('/a')


def test_prefix_namespace_puts_relative_under_base_and_drops_trailing_slashes():
    assert prefix_namespace(None, None) is None
    assert prefix_namespace('my_ns', None) == 'my_ns'
    assert prefix_namespace(None, 'inner') == 'inner'
    assert prefix_namespace('my_ns', 'inner') == 'my_ns/inner'
    assert prefix_namespace('/my_ns', 'inner/') == '/my_ns/inner'
    assert prefix_namespace('my_ns', '/inner') == '/inner'
    assert prefix_namespace('/', 'inner') == '/inner'
    assert prefix_namespace('/', None) == '/'


def test_make_namespace_absolute_only_adds_a_leading_slash():
    assert make_namespace_absolute(None) is None
    assert make_namespace_absolute('a/b') == '/a/b'
    assert make_namespace_absolute('/a') == '/a'
    assert make_namespace_absolute('') == '/'


def test_normalize_parameters_gives_a_tuple_of_upstreams_shapes():
    described = ParameterDescription('rate', 5)
    normalized = normalize_parameters(['/tmp/p.yaml', pathlib.Path('/tmp/q.yaml'), described,
                                       {'outer': {'inner': 1}, 'flag': True}])
    assert isinstance(normalized, tuple)
    assert len(normalized) == 4
    assert all(isinstance(item, ParameterFile) for item in normalized[:2])
    assert normalized[2] is described
    names = [perform_substitutions(LaunchContext(), list(key)) for key in normalized[3]]
    assert all(isinstance(key, tuple) for key in normalized[3])
    assert names == ['outer.inner', 'flag']


def test_normalize_parameters_refuses_text_a_dict_and_bare_values():
    for wrong in ('p.yaml', {'a': 1}, iter([{'a': 1}])):
        with pytest.raises(TypeError, match='parameters must be a list'):
            normalize_parameters(wrong)
    with pytest.raises(TypeError, match='Parameter objects'):
        normalize_parameters([5.0])


def test_evaluate_parameters_types_values_and_gives_tuples_for_lists():
    [values] = evaluated({'text': 'owl', 'quoted_number': '5', 'number': 5, 'ratio': 0.5, 'ints': [1, 2],
                          'mixed': [1, 2.5], 'words': ['a', 'b'], 'flags': [True, False],
                          'from_yaml': TextSubstitution(text='[3, 4]'),
                          'joined': [TextSubstitution(text='4'), '2'],
                          'typed': ParameterValue(TextSubstitution(text='7'), value_type=str),
                          'nested': {'deeper': 'x'}})
    assert values == {'text': 'owl', 'quoted_number': '5', 'number': 5, 'ratio': 0.5, 'ints': (1, 2),
                      'mixed': (1.0, 2.5), 'words': ('a', 'b'), 'flags': (True, False), 'from_yaml': (3, 4),
                      'joined': 42, 'typed': '7', 'nested.deeper': 'x'}


def test_evaluate_parameters_gives_paths_and_passes_parameter_descriptions_on():
    described = ParameterDescription('rate', 5)
    result = evaluated('/tmp/p.yaml', described)
    assert isinstance(result, tuple)
    assert isinstance(result[0], pathlib.Path)
    assert result[0] == pathlib.Path('/tmp/p.yaml')
    assert result[1] is described


def test_evaluate_parameters_refuses_parameters_that_were_not_normalized():
    with pytest.raises(TypeError, match='normalize_parameters'):
        evaluate_parameters(LaunchContext(), [{'a': 1}])
    with pytest.raises(TypeError, match='normalize_parameters'):
        evaluate_parameters(LaunchContext(), ['/tmp/p.yaml'])


def test_evaluate_parameters_refuses_a_list_of_mixed_types():
    with pytest.raises(TypeError, match="'odd'"):
        evaluated({'odd': ['a', 1]})


def test_remap_rules_normalize_to_tuples_lazily():
    rules = normalize_remap_rules([('a', 'b')])
    assert not isinstance(rules, (list, tuple))  # a generator, as upstream's
    [(source, target)] = list(rules)
    assert isinstance(source, tuple)
    assert isinstance(target, tuple)
    assert perform_substitutions(LaunchContext(), list(target)) == 'b'
    with pytest.raises(TypeError, match='length 2'):
        normalize_remap_rule(('a', 'b', 'c'))


def test_to_parameters_list_types_dicts_descriptions_and_this_nodes_file_sections(tmp_path):
    path = tmp_path / 'params.yaml'
    path.write_text('/**:\n  ros__parameters:\n    shared: 1\n    rate: 1.0\n'
                    '/lab/owl:\n  ros__parameters:\n    rate: 2.5\n    names: [a, b]\n'
                    '/lab/other:\n  ros__parameters:\n    ignored: true\n')
    items = evaluated({'label': 'x', 'ids': [1, 2]}, str(path), ParameterDescription('loud', True))
    parameters = to_parameters_list(LaunchContext(), 'owl', '/lab', items)
    assert all(isinstance(p, rclpy.parameter.Parameter) for p in parameters)
    found = {p.name: (p.type_, p.value) for p in parameters}
    kind = rclpy.parameter.Parameter.Type
    assert found == {
        'label': (kind.STRING, 'x'), 'ids': (kind.INTEGER_ARRAY, (1, 2)), 'shared': (kind.INTEGER, 1),
        'rate': (kind.DOUBLE, 2.5), 'names': (kind.STRING_ARRAY, ('a', 'b')), 'loud': (kind.BOOL, True)}


def test_to_parameters_list_refuses_what_is_not_an_evaluated_parameter():
    with pytest.raises(RuntimeError, match='invalid evaluated parameters'):
        to_parameters_list(LaunchContext(), 'owl', '/', ['not a path object'])


def test_plugin_versions_are_caret_ranges():
    assert get_upper_bound_caret_version(Version('0.1')) == Version('0.2.0')
    assert get_upper_bound_caret_version(Version('1.4.2')) == Version('2.0.0')
    satisfies_version('0.1.3', '^0.1')
    with pytest.raises(PluginException, match='newer'):
        satisfies_version('0.2', '^0.1')
    with pytest.raises(PluginException, match='too old'):
        satisfies_version('1.0', '^1.2')
    with pytest.raises(ValueError, match='caret'):
        satisfies_version('1.0', '>=1.0')


# ---- composition ----

def test_load_request_helper_refuses_in_one_line():
    with pytest.raises(CompositionUnavailableError) as error:
        get_composable_node_load_request(object(), LaunchContext())
    assert 'composition_interfaces' in str(error.value)
    assert '\n' not in str(error.value)


# ---- $(param name default) ----

def test_param_default_is_used_only_when_the_parameter_was_not_set():
    context = LaunchContext()
    assert Parameter('missing', default='fallback').perform(context) == 'fallback'
    assert Parameter('missing', default=5).perform(context) == '5'
    assert Parameter('missing', default=[TextSubstitution(text='a'), 1]).perform(context) == 'a1'
    assert Parameter('missing', default='').perform(context) == ''
    SetParameter('present', 'set').visit(context)
    assert Parameter('present', default='fallback').perform(context) == 'set'
    with pytest.raises(SubstitutionFailure, match="parameter 'missing' not found"):
        Parameter('missing').perform(context)


def test_param_default_in_a_launch_file(tmp_path, capsys):
    path = tmp_path / 'p.launch.xml'
    path.write_text('<launch><log message="mode $(param mode slow)"/></launch>')
    root, parser = Parser.load(path)
    service = LaunchService(noninteractive=True)
    service.include_launch_description(parser.parse_description(root))
    assert service.run() == 0
    assert '[INFO] [launch.user]: mode slow' in capsys.readouterr().out


# ---- Node ----

def test_node_name_is_refused_before_execution():
    node = Node(executable='true', name='owl')
    with pytest.raises(RuntimeError, match="cannot access 'node_name' before executing action"):
        _ = node.node_name


@pytest.mark.parametrize(('kwargs', 'scope', 'full_name', 'complete'), [
    ({'name': 'owl', 'namespace': 'lab'}, [], '/lab/owl', True),
    ({'name': 'owl'}, [PushRosNamespace('lab')], '/lab/owl', True),
    ({'name': 'owl', 'namespace': ''}, [], '/owl', True),
    ({'name': 'owl'}, [], '<node_namespace_unspecified>/owl', False),
    ({'namespace': 'lab'}, [], '/lab/<node_name_unspecified>', False),
])
def test_unspecified_parts_of_the_node_name(kwargs, scope, full_name, complete):
    node = Node(executable='true', **kwargs)
    prepare(node, *scope)
    assert node.node_name == full_name
    assert node.is_node_name_fully_specified() is complete
    assert Node.UNSPECIFIED_NODE_NAME == '<node_name_unspecified>'
    assert Node.UNSPECIFIED_NODE_NAMESPACE == '<node_namespace_unspecified>'


def test_expanded_namespace_and_remappings_when_none_were_given():
    node = Node(executable='true', name='owl')
    prepare(node)
    assert node.expanded_node_namespace == Node.UNSPECIFIED_NODE_NAMESPACE
    assert node.expanded_remapping_rules is None


def test_node_package_and_executable_are_kept_as_given():
    package = TextSubstitution(text='pkg')
    node = Node(package=package, executable='exe')
    assert node.node_package is package
    assert node.node_executable == 'exe'
    assert Node(executable='exe').node_package is None


def test_parse_nested_parameters_reads_param_entities(tmp_path):
    path = tmp_path / 'n.launch.xml'
    path.write_text('<launch><node exec="true"><param name="outer"><param name="inner" value="3"/>'
                    '</param></node></launch>')
    root, parser = Parser.load(path)
    [node_entity] = root.action_children()
    [parameters] = Node.parse_nested_parameters(node_entity.get_children('param'), parser)
    [value] = parameters['outer'].values()
    assert perform_substitutions(LaunchContext(), value) == '3'


def test_no_duplicate_name_warning_without_a_namespace(capsys):
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription([
        Node(executable='true', name='twin'), Node(executable='true', name='twin')]))
    assert service.run() == 0
    assert 'nodes with the name' not in capsys.readouterr().out


def test_node_action_extensions_add_arguments_and_change_ros_arguments(monkeypatch):
    class Renaming(node_module.NodeActionExtension):
        def prepare_for_execute(self, context, ros_specific_arguments, node_action):
            assert node_action.node_name == '/lab/owl'
            renamed = {**ros_specific_arguments, 'name': '__node:=renamed'}
            return ['--extra', TextSubstitution(text='x')], renamed

    class TooNew(node_module.NodeActionExtension):
        EXTENSION_POINT_VERSION = '0.2'

    def entry_point(name, cls):
        return types.SimpleNamespace(name=name, load=lambda: cls)

    monkeypatch.setattr(node_module, 'get_entry_points', lambda group: [
        entry_point('renaming', Renaming), entry_point('too_new', TooNew)])
    node = Node(executable='true', name='owl', namespace='lab')
    argv = prepare(node)
    assert argv[1:] == ['--ros-args', '-r', '__node:=renamed', '-r', '__ns:=/lab', '--extra', 'x']
    [extension] = node_module.get_extensions(types.SimpleNamespace(warning=lambda message: None)).values()
    assert extension.NAME == 'renaming'


# ---- lifecycle ----

def transition_event(action, start: str, goal: str) -> StateTransition:
    message = lifecycle_msgs.msg.TransitionEvent()
    message.start_state.label = start
    message.goal_state.label = goal
    return StateTransition(action=action, msg=message)


def test_lifecycle_transition_matchers_add_the_leading_slash():
    owl = types.SimpleNamespace(node_name='/owl')
    assert match_node_name_goal('owl', 'active')(transition_event(owl, 'activating', 'active'))
    assert not match_node_name_goal('owl', 'inactive')(transition_event(owl, 'activating', 'active'))
    assert match_node_name_start_goal('/owl', 'activating', 'active')(
        transition_event(owl, 'activating', 'active'))
    assert not match_node_name_start_goal('owl', 'configuring', 'active')(
        transition_event(owl, 'activating', 'active'))
    assert not match_node_name_goal('owl', 'active')(LogInfo(msg='not an event'))


def test_lifecycle_node_without_a_namespace_is_in_the_pushed_or_root_one():
    alone = LifecycleNode(executable='true', name='owl')
    prepare(alone)
    assert alone.node_name == '/owl'
    assert alone.is_node_name_fully_specified()
    pushed = LifecycleNode(executable='true', name='owl')
    prepare(pushed, PushRosNamespace('lab'))
    assert pushed.node_name == '/lab/owl'


# ---- parameter descriptions ----

def test_parameter_description_gives_value_and_type_as_given():
    described = ParameterDescription('rate', '5', value_type=int)
    assert described.value == '5'
    assert described.value_type is int
    assert described.evaluate(LaunchContext()) == ('rate', 5)


def test_parameter_file_gives_a_path_and_cleanup_removes_only_its_substituted_copy(tmp_path):
    path = tmp_path / 'p.yaml'
    path.write_text('a: $(env HOME)\n')
    plain = ParameterFile(str(path))
    assert plain.evaluate(LaunchContext()) == path
    plain.cleanup()
    substituted = ParameterFile(path, allow_substs=True)
    copy = substituted.evaluate(LaunchContext())
    assert isinstance(copy, pathlib.Path)
    assert copy != path
    assert copy.read_text() == f"a: {os.environ['HOME']}\n"
    substituted.cleanup()
    assert not copy.exists()
    assert path.exists()


def test_ros_adapter_keeps_its_argv():
    assert ROSAdapter(argv=['--ros-args'], autostart=False).argv == ['--ros-args']
