"""What upstream launch documents, checked on ours.

Its module paths, the actions and frontend pieces added for issue 13, and the behaviours that used to
differ.
"""

import asyncio
import importlib
import io

import pytest
from launch import Condition, LaunchContext, LaunchDescription, LaunchService
from launch.actions import (
    ExecuteProcess,
    GroupAction,
    LogInfo,
    OpaqueCoroutine,
    RegisterEventHandler,
    ResetLaunchConfigurations,
    SetLaunchConfiguration,
    TimerAction,
)
from launch.frontend import LaunchFileError, Parser
from launch.substitutions import (
    Command,
    EqualsSubstitution,
    LaunchConfiguration,
    NotSubstitution,
    SubstitutionFailure,
)
from launch.utilities.type_utils import coerce_to_type, get_typed_value

pytestmark = pytest.mark.usefixtures('isolated_launch')

# Module path -> a name upstream code imports from it.
UPSTREAM_PATHS = {
    'launch.event_handlers.on_process_exit': 'OnProcessExit',
    'launch.event_handlers.on_process_start': 'OnProcessStart',
    'launch.event_handlers.on_process_io': 'OnProcessIO',
    'launch.event_handlers.on_shutdown': 'OnShutdown',
    'launch.event_handlers.on_include_launch_description': 'OnIncludeLaunchDescription',
    'launch.actions.execute_process': 'ExecuteProcess',
    'launch.actions.emit_event': 'EmitEvent',
    'launch.actions.declare_launch_argument': 'DeclareLaunchArgument',
    'launch.actions.opaque_coroutine': 'OpaqueCoroutine',
    'launch.actions.reset_launch_configurations': 'ResetLaunchConfigurations',
    'launch.substitutions.substitution_failure': 'SubstitutionFailure',
    'launch.substitutions.launch_configuration': 'LaunchConfiguration',
    'launch.substitutions.boolean_substitution': 'NotSubstitution',
    'launch.utilities.type_utils': 'get_typed_value',
    'launch.utilities.perform_substitutions_impl': 'perform_substitutions',
    'launch.events.process.process_exited': 'ProcessExited',
    'launch.events.process.process_matchers': 'matches_name',
    'launch.launch_description_sources.python_launch_description_source': 'PythonLaunchDescriptionSource',
    'launch.some_substitutions_type': 'SomeSubstitutionsType',
    'launch.some_entities_type': 'SomeEntitiesType',
    'launch.invalid_launch_file_error': 'InvalidLaunchFileError',
    'launch.launch_introspector': 'LaunchIntrospector',
    'launch.frontend.parser': 'Parser',
    'launch.frontend.parse_substitution': 'parse_substitution',
    'launch.launch_description_sources.any_launch_description_source': 'AnyLaunchDescriptionSource',
    'launch.some_actions_type': 'SomeActionsType',
    'launch_xml.launch_description_sources.xml_launch_description_source': 'XMLLaunchDescriptionSource',
    'launch_yaml.launch_description_sources.yaml_launch_description_source': 'YAMLLaunchDescriptionSource',
}


def run(*entities) -> int:
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription(list(entities)))
    return service.run()


def user_lines(capsys) -> list[str]:
    return [line.split(': ', 1)[1] for line in capsys.readouterr().out.splitlines()
            if line.startswith('[INFO] [launch.user]')]


@pytest.mark.parametrize('module', UPSTREAM_PATHS)
def test_upstream_module_paths_give_the_one_implementation(module):
    name = UPSTREAM_PATHS[module]
    imported = getattr(importlib.import_module(module), name)
    package = importlib.import_module(module.rsplit('.', 1)[0])
    # The same object as the package-level name, not a second implementation.
    assert getattr(package, name, imported) is imported


def test_reset_launch_configurations_keeps_only_what_it_is_given(capsys):
    assert run(
        SetLaunchConfiguration('robot', 'owl'), SetLaunchConfiguration('speed', 'fast'),
        GroupAction([
            ResetLaunchConfigurations({'name': LaunchConfiguration('robot')}),
            LogInfo(msg=LaunchConfiguration('name')),
            LogInfo(msg=LaunchConfiguration('speed', default='forgotten')),
        ]),
        LogInfo(msg=LaunchConfiguration('speed')),
    ) == 0
    assert user_lines(capsys) == ['owl', 'forgotten', 'fast']


def test_reset_tag_in_xml_and_yaml(tmp_path, capsys):
    xml = tmp_path / 'reset.launch.xml'
    xml.write_text('<launch><let name="a" value="1"/><let name="b" value="2"/>'
                   '<reset><keep name="c" value="$(var a)"/></reset>'
                   '<log message="$(var c) $(var a 0) $(var b 0)"/></launch>')
    yaml_file = tmp_path / 'reset.launch.yaml'
    yaml_file.write_text('launch:\n- let: {name: a, value: x}\n- reset: {}\n'
                         '- log: {message: $(var a gone)}\n')
    for path in (xml, yaml_file):
        root, parser = Parser.load(str(path))
        assert run(parser.parse_description(root)) == 0
    assert user_lines(capsys) == ['1 0 0', 'gone']


def test_reset_refuses_a_list():
    with pytest.raises(TypeError, match='dict of launch configurations'):
        ResetLaunchConfigurations(['a'])


def test_opaque_coroutine_keeps_launch_up_until_it_returns(capsys):
    async def slow(context, word):
        await asyncio.sleep(0.2)
        print(f'[INFO] [launch.user]: coroutine {word} {context.launch_configurations["x"]}')

    assert run(SetLaunchConfiguration('x', 'seen'),
               OpaqueCoroutine(coroutine=slow, args=['done'])) == 0
    assert user_lines(capsys) == ['coroutine done seen']


def test_opaque_coroutine_is_cancelled_at_shutdown(capsys):
    async def forever():
        await asyncio.sleep(60)
        print('[INFO] [launch.user]: never')

    from launch.actions import Shutdown

    assert run(OpaqueCoroutine(coroutine=forever, ignore_context=True),
               TimerAction(period=0.1, actions=[Shutdown()])) == 0
    assert user_lines(capsys) == []


def test_opaque_coroutine_needs_an_async_function():
    with pytest.raises(TypeError, match="'async def' function"):
        OpaqueCoroutine(coroutine=lambda context: None)


def test_callable_target_action_selects_processes(capsys):
    from launch.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart

    first = ExecuteProcess(cmd=['echo', 'one'], name='first')
    second = ExecuteProcess(cmd=['echo', 'two'], name='second')

    def is_second(action):
        return action is second

    heard = []
    assert run(
        RegisterEventHandler(OnProcessStart(target_action=is_second, on_start=[LogInfo(msg='started')])),
        RegisterEventHandler(OnProcessExit(target_action=is_second, on_exit=[LogInfo(msg='exited')])),
        RegisterEventHandler(OnProcessIO(target_action=is_second,
                                         on_stdout=lambda event: heard.append(event.text))),
        first, second,
    ) == 0
    assert user_lines(capsys) == ['started', 'exited']
    assert b''.join(heard) == b'two\n'


def test_process_handlers_refuse_a_target_that_runs_no_process():
    from launch.event_handlers import OnProcessExit

    with pytest.raises(TypeError, match='ExecuteProcess'):
        OnProcessExit(target_action=LogInfo(msg='x'), on_exit=[])


def test_on_include_launch_description_visits_the_included_description(capsys):
    from launch.event_handlers import OnIncludeLaunchDescription
    from launch.events import IncludeLaunchDescription

    handler = OnIncludeLaunchDescription()
    description = LaunchDescription([LogInfo(msg='included')])
    event = IncludeLaunchDescription(description)
    assert handler.matches(event)
    assert handler.handle(event, LaunchContext()) == [description]


def test_parser_load_reads_paths_and_streams(tmp_path):
    path = tmp_path / 'x.launch.xml'
    path.write_text('<launch><arg name="a" default="1"/></launch>')
    root, parser = Parser.load(path)
    assert [a.name for a in parser.parse_description(root).get_launch_arguments()] == ['a']
    stream = io.StringIO('launch:\n- arg: {name: b}\n')
    root, parser = Parser.load(stream)
    assert [a.name for a in parser.parse_description(root).get_launch_arguments()] == ['b']
    assert Parser.is_filename_valid('a.launch.yaml')
    assert not Parser.is_filename_valid('a.launch.py')


def test_parser_load_of_a_missing_file_says_so(tmp_path):
    with pytest.raises(LaunchFileError, match='does not exist'):
        Parser.load(str(tmp_path / 'nope.xml'))


@pytest.mark.parametrize(('text', 'expected'), [
    ('yes', True), ('on', True), ('True', True), ('no', False), ('off', False), ('false', False)])
def test_yaml_booleans_as_upstream_types_them(text, expected):
    assert coerce_to_type(text, bool) is expected


def test_typed_values_follow_yaml():
    assert get_typed_value('5', int) == 5
    assert get_typed_value(['1', '2'], list[int]) == [1, 2]
    with pytest.raises(ValueError, match='bool'):
        coerce_to_type('maybe', bool)


def test_frontend_boolean_attributes_accept_yes_and_on(tmp_path, capsys):
    path = tmp_path / 'g.launch.xml'
    path.write_text('<launch><let name="v" value="outer"/>'
                    '<group scoped="yes"><let name="v" value="inner"/></group>'
                    '<group scoped="off"><let name="w" value="leaked"/></group>'
                    '<log message="$(var v) $(var w)"/></launch>')
    root, parser = Parser.load(path)
    assert run(parser.parse_description(root)) == 0
    assert user_lines(capsys) == ['outer leaked']


def test_respawn_accepts_yes(capsys):
    process = ExecuteProcess(cmd=['true'], respawn='yes', respawn_max_retries=1, output='screen')
    assert run(process) == 0
    assert capsys.readouterr().out.count('process started with pid') == 2


def test_bare_condition_is_false(capsys):
    assert Condition().evaluate(LaunchContext()) is False
    assert run(LogInfo(msg='hidden', condition=Condition())) == 0
    assert user_lines(capsys) == []


@pytest.mark.parametrize(('left', 'right', 'expected'), [
    (None, None, 'true'), (None, '', 'true'), (True, 'true', 'true'), (True, '1', 'true'),
    (1.0, '1', 'true'), ('a', 'b', 'false'), (False, None, 'false')])
def test_equals_substitution_compares_any_values(left, right, expected):
    assert EqualsSubstitution(left, right).perform(LaunchContext()) == expected


def test_not_substitution_of_a_non_boolean_is_a_substitution_failure():
    with pytest.raises(SubstitutionFailure, match="'maybe' is not a valid boolean"):
        NotSubstitution('maybe').perform(LaunchContext())


def test_command_on_a_missing_file_says_file_not_found(tmp_path):
    missing = tmp_path / 'no_such_script'
    with pytest.raises(SubstitutionFailure, match=f"file not found: '{missing}'"):
        Command(str(missing)).perform(LaunchContext())
