"""Jazzy's public launch surface as third-party launch code meets it: names, signatures, behaviours."""

import asyncio
import os
import signal
import sys
import warnings
from typing import List  # noqa: UP035 (launch-file code written for upstream uses it)

import pytest
from launch import LaunchContext, LaunchDescription, LaunchService
from launch.action import Action
from launch.actions import (
    ExecuteLocal,
    ExecuteProcess,
    GroupAction,
    IncludeLaunchDescription,
    LogInfo,
    OpaqueCoroutine,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    RegisterEventHandler,
    Shutdown,
    TimerAction,
)
from launch.conditions import LaunchConfigurationEquals
from launch.descriptions import Executable
from launch.event_handlers import OnProcessIO
from launch.events.process import ProcessStdout
from launch.frontend import Entity, Parser, expose_action, expose_substitution, load_launch_file
from launch.frontend.expose import substitution_parse_methods
from launch.frontend.parse_substitution import parse_if_substitutions, parse_substitution
from launch.invalid_launch_file_error import InvalidLaunchFileError
from launch.launch_description_sources import (
    InvalidFrontendLaunchFileError,
    get_launch_description_from_frontend_launch_file,
)
from launch.substitution import Substitution
from launch.substitutions import (
    AllSubstitution,
    AnySubstitution,
    IfElseSubstitution,
    OrSubstitution,
    SubstitutionFailure,
    TextSubstitution,
)
from launch.utilities import (
    AsyncSafeSignalManager,
    isclassinstance,
    normalize_to_list_of_entities,
    perform_substitutions,
    visit_all_entities_and_collect_futures,
)
from launch.utilities.type_utils import coerce_to_type, is_normalized_substitution

pytestmark = pytest.mark.usefixtures('isolated_launch')


def run(*entities) -> int:
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription(list(entities)))
    return service.run()


def xml_file(tmp_path, body: str) -> str:
    path = tmp_path / 'surface.launch.xml'
    path.write_text(f'<launch>\n{body}\n</launch>\n')
    return str(path)


def test_normalize_to_list_of_entities_flattens_one_level():
    first, second, third = LogInfo(msg='a'), LogInfo(msg='b'), LogInfo(msg='c')
    assert normalize_to_list_of_entities([first, [second, third]]) == [first, second, third]
    with pytest.raises(TypeError, match="got 'int'"):
        normalize_to_list_of_entities([first, 3])


def test_isclassinstance_holds_for_any_object():
    assert isclassinstance(3)
    assert isclassinstance(LogInfo)


def test_is_normalized_substitution_means_a_non_empty_list_of_substitutions():
    assert is_normalized_substitution([TextSubstitution(text='x')])
    assert not is_normalized_substitution([])
    assert not is_normalized_substitution(['x'])
    assert not is_normalized_substitution(TextSubstitution(text='x'))


def test_parse_if_substitutions_keeps_plain_values_and_parses_dollar_text():
    assert parse_if_substitutions('plain') == 'plain'
    assert parse_if_substitutions(2.5) == 2.5
    assert parse_if_substitutions([1, 2]) == [1, 2]
    parsed = Parser().parse_if_substitutions('$(var x)')
    assert is_normalized_substitution(parsed)
    with pytest.raises(ValueError, match='several types'):
        parse_if_substitutions([1, 'a'])


def test_frontend_file_errors_are_invalid_launch_file_errors(tmp_path):
    broken = tmp_path / 'broken.launch.xml'
    broken.write_text('<launch><log')
    assert issubclass(InvalidFrontendLaunchFileError, InvalidLaunchFileError)
    with pytest.raises(InvalidFrontendLaunchFileError, match=r'format \[xml\]'):
        get_launch_description_from_frontend_launch_file(str(broken))


def test_executable_takes_upstreams_keywords_and_prepares_them():
    executable = Executable(cmd=['/bin/echo', 'a'], arguments=['b'], name='speaker', cwd='/tmp',
                            env={'ONLY': '1'}, additional_env={'MORE': '2'})
    assert len(executable.cmd) == 3
    assert executable.arguments == ['b']
    executable.prepare(LaunchContext(), LogInfo(msg='unused'))
    assert executable.final_cmd == ['/bin/echo', 'a', 'b']
    assert executable.final_name.startswith('speaker-')
    assert executable.final_cwd == '/tmp'
    assert executable.final_env == {'ONLY': '1', 'MORE': '2'}
    with pytest.raises(TypeError, match='must be a list'):
        Executable(cmd='echo')


def test_execute_local_runs_a_process_description_and_fills_process_details():
    action = ExecuteLocal(process_description=Executable(cmd=[sys.executable, '-c', 'pass']))
    assert isinstance(action, Action)
    assert not isinstance(action, ExecuteProcess)
    assert action.process_details is None
    assert run(action) == 0
    details = action.process_details
    assert details['action'] is action
    assert details['cmd'][0] == sys.executable
    assert {'name', 'cwd', 'env'} <= set(details)
    assert isinstance(details['pid'], int)
    with pytest.raises(TypeError, match='Executable'):
        ExecuteLocal(process_description=['echo'])


def test_get_sub_entities_of_actions_groups_includes_and_processes(tmp_path):
    assert LogInfo(msg='x').get_sub_entities() == []
    inner = LogInfo(msg='inner')
    group = GroupAction([inner]).get_sub_entities()
    assert isinstance(group[0], PushLaunchConfigurations)
    assert isinstance(group[-1], PopLaunchConfigurations)
    assert inner in group
    assert GroupAction([inner], scoped=False).get_sub_entities() == [inner]
    stop = Shutdown()
    assert ExecuteProcess(cmd=['true'], on_exit=[stop]).get_sub_entities() == [stop]
    included = IncludeLaunchDescription(xml_file(tmp_path, '<log message="hi"/>')).get_sub_entities()
    assert len(included) == 1
    assert isinstance(included[0], LaunchDescription)


def test_launch_context_performs_one_substitution():
    assert LaunchContext().perform_substitution(TextSubstitution(text='t')) == 't'


def test_shutdown_of_a_service_that_is_not_running_does_nothing():
    service = LaunchService(noninteractive=True)
    assert service.shutdown() is None
    service.include_launch_description(LaunchDescription([LogInfo(msg='still runs')]))
    assert service.run() == 0


def test_shutdown_from_inside_the_loop_returns_a_coroutine():
    service = LaunchService(noninteractive=True)
    returned = []

    async def stop(context):
        result = service.shutdown()
        returned.append(result)
        await result

    service.include_launch_description(LaunchDescription([
        TimerAction(period=30.0, actions=[LogInfo(msg='too late')]), OpaqueCoroutine(coroutine=stop)]))
    assert service.run() == 0
    assert len(returned) == 1
    assert asyncio.iscoroutine(returned[0])


class Shout(Substitution):
    """A third-party substitution exposed the upstream way."""

    def __init__(self, word):
        self.word = word

    @classmethod
    def parse(cls, data):
        if len(data) != 1:
            raise TypeError('shout takes one argument')
        return cls, {'word': data[0]}

    def perform(self, context):
        return perform_substitutions(context, self.word).upper()


def test_third_party_substitution_class_with_parse_works_in_launch_files(tmp_path):
    expose_substitution('shout')(Shout)
    try:
        context = LaunchContext()
        context.launch_configurations['w'] = 'hey'
        assert perform_substitutions(context, parse_substitution('$(shout $(var w))!')) == 'HEY!'
        description = load_launch_file(xml_file(tmp_path, '<let name="x" value="$(shout low)"/>'), 'xml')
        context = LaunchContext()
        for entity in description.entities:
            entity.visit(context)
        assert context.launch_configurations['x'] == 'LOW'
        with pytest.raises(TypeError, match='one argument'):
            parse_substitution('$(shout a b)')
    finally:
        del substitution_parse_methods['shout']


def test_exposing_a_class_without_parse_is_an_error():
    with pytest.raises(RuntimeError, match="no 'parse' classmethod"):
        expose_substitution('nothing')(TextSubstitution)


def test_an_action_may_be_exposed_through_a_parse_function(tmp_path):
    @expose_action('shout_log')
    def parse_shout_log(entity, parser):
        return LogInfo, {'msg': entity.get_attr('message').upper()}

    description = load_launch_file(xml_file(tmp_path, '<shout_log message="hi"/>'), 'xml')
    [action] = description.entities
    assert isinstance(action, LogInfo)


def test_an_actions_parser_reads_nested_tags_the_upstream_way(tmp_path):
    @expose_action('say_lines')
    def parse_say_lines(entity, parser):
        lines = entity.get_attr('line', data_type=List[Entity])  # noqa: UP006 (as upstream's code writes it)
        assert all(line.parent is entity for line in lines)
        return LogInfo, {'msg': ' / '.join(line.get_attr('text') for line in lines)}

    xml = load_launch_file(xml_file(tmp_path, '<say_lines><line text="a"/><line text="b"/></say_lines>'),
                           'xml')
    yaml_path = tmp_path / 'surface.launch.yaml'
    yaml_path.write_text('launch:\n- say_lines:\n    line:\n    - text: a\n    - text: b\n')
    for description in (xml, load_launch_file(str(yaml_path), 'yaml')):
        [action] = description.entities
        assert [sub.text for sub in action.msg] == ['a / b']

    root, _parser = Parser.load(xml_file(tmp_path, '<group><log message="x"/></group>'))
    [group] = root.children
    assert [child.type_name for child in group.children] == ['log']
    assert group.get_attr('missing', data_type=list[Entity], optional=True) is None
    with pytest.raises(ValueError, match="Nested tag 'missing' of type 'group' not found"):
        group.get_attr('missing', data_type=list[Entity])


def test_timer_period_is_read_as_a_float_and_a_string_literal_warns(tmp_path):
    description = load_launch_file(xml_file(tmp_path, '<timer period="2"><log message="x"/></timer>'), 'xml')
    assert description.entities[0].period == 2.0
    with pytest.warns(UserWarning, match='string literal'):
        timer = TimerAction(period='1.5', actions=[])
    assert timer.period == 1.5
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        with pytest.raises(ValueError, match='number of seconds'):
            TimerAction(period='soon', actions=[])


def test_process_attributes_are_typed_as_upstream_types_them(tmp_path):
    description = load_launch_file(xml_file(
        tmp_path, '<executable cmd="true" sigterm_timeout="3" emulate_tty="on" respawn_delay="1"/>'), 'xml')
    [process] = description.entities
    assert perform_substitutions(LaunchContext(), process.sigterm_timeout) == '3.0'
    assert process.emulate_tty is True
    assert process.respawn_delay == 1.0
    with pytest.raises(ValueError, match='must not be negative'):
        load_launch_file(xml_file(tmp_path, '<executable cmd="true" sigkill_timeout="-1"/>'), 'xml')
    with pytest.raises(ValueError, match='must be a float'):
        load_launch_file(xml_file(tmp_path, '<executable cmd="true" sigkill_timeout="soon"/>'), 'xml')


def test_entity_get_attr_converts_to_the_requested_type(tmp_path):
    root, _parser = Parser.load(xml_file(tmp_path, '<log message="1" level="x"/>'))
    [entity] = root.action_children()
    assert entity.get_attr('message', data_type=int) == 1
    assert entity.get_attr('message', data_type=bool) is True
    assert entity.get_attr('level', data_type=float) == 'x'  # can_be_str keeps text
    with pytest.raises(ValueError, match="attribute 'level'"):
        entity.get_attr('level', data_type=float, can_be_str=False)


def test_boolean_substitutions_check_every_argument():
    context = LaunchContext()
    with pytest.raises(SubstitutionFailure, match="'maybe' is not a valid boolean"):
        OrSubstitution('true', 'maybe').perform(context)
    with pytest.raises(SubstitutionFailure, match="'maybe'"):
        AnySubstitution('1', 'maybe').perform(context)
    with pytest.raises(SubstitutionFailure, match="'maybe'"):
        AllSubstitution('0', 'maybe').perform(context)


def test_bool_text_is_read_as_jazzy_reads_it():
    context = LaunchContext()
    assert IfElseSubstitution('on', 'yes', 'no').perform(context) == 'yes'
    assert IfElseSubstitution('0', 'yes', 'no').perform(context) == 'no'
    assert coerce_to_type('1', bool) is True
    assert coerce_to_type('off', bool) is False
    with pytest.raises(RuntimeError, match='if_value or else_value'):
        IfElseSubstitution('true')


def test_on_process_io_without_callbacks_still_matches_the_targets_output():
    process = ExecuteProcess(cmd=['true'])
    handler = OnProcessIO(target_action=process)
    event = ProcessStdout(action=process, name='true-1', cmd=['true'], cwd=None, env=None, pid=1,
                          text=b'x\n')
    assert handler.matches(event)
    assert handler.handle(event, LaunchContext()) is None
    assert run(RegisterEventHandler(OnProcessIO(on_stdout=lambda event: None))) == 0


def test_deprecations_launch_file_authors_meet_are_shown():
    with pytest.warns(UserWarning, match='deprecated'):
        LaunchConfigurationEquals('mode', 'fast')
    with pytest.warns(UserWarning, match='is_filename_valid'):
        assert Parser.is_extension_valid('xml')
    with pytest.warns(UserWarning, match='get_parsers_from_filename'):
        Parser.get_parser_from_extension('yaml')
    assert [parser.__module__ for parser in Parser.get_parsers_from_filename('a.launch.yml')] == \
        ['launch_yaml.parser']



def test_visiting_collects_each_entitys_future_depth_first():
    context = LaunchContext()
    first, second = TimerAction(period=30.0, actions=[]), TimerAction(period=30.0, actions=[])

    async def visit():
        context._asyncio_loop = asyncio.get_running_loop()
        found = visit_all_entities_and_collect_futures(
            GroupAction([first, LogInfo(msg='no future'), GroupAction([second])]), context)
        for _, future in found:
            future.cancel()
        return found

    found = asyncio.run(visit())
    assert [entity for entity, _ in found] == [first, second]
    with pytest.raises(TypeError, match="expected a launch description entity, got 'str'"):
        visit_all_entities_and_collect_futures('not an entity', context)


def test_signal_manager_runs_handlers_in_the_loop_for_its_block():
    heard = []

    async def main():
        loop = asyncio.get_running_loop()
        with AsyncSafeSignalManager(loop) as signals:
            assert signals.handle(signal.SIGUSR1, heard.append) is None
            os.kill(os.getpid(), signal.SIGUSR1)
            await asyncio.sleep(0.2)
            assert signals.handle(signal.SIGUSR1, None) == heard.append
            signals.handle(signal.SIGUSR2, heard.append)
        # Leaving the block took SIGUSR2's handler away: the loop has none for it.
        assert not loop.remove_signal_handler(signal.SIGUSR2)

    asyncio.run(main())
    assert heard == [signal.SIGUSR1]
