"""The launch core in-process: scoping, environment, conditions, errors and return codes."""

import os
import re
import signal
import sys
import threading

import pytest
from launch import LaunchDescription, LaunchService
from launch.actions import (
    AppendEnvironmentVariable,
    DeclareLaunchArgument,
    EmitEvent,
    ExecuteProcess,
    GroupAction,
    LogInfo,
    OpaqueFunction,
    RegisterEventHandler,
    SetEnvironmentVariable,
    SetLaunchConfiguration,
    TimerAction,
    UnsetEnvironmentVariable,
)
from launch.conditions import IfCondition
from launch.event_handlers import OnProcessStart
from launch.events import matches_action
from launch.events.process import ShutdownProcess, SignalProcess
from launch.substitutions import (
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    IfElseSubstitution,
    LaunchConfiguration,
    NotSubstitution,
    PythonExpression,
)

pytestmark = pytest.mark.usefixtures('isolated_launch')


def run(*entities, argv=None) -> int:
    service = LaunchService(argv=argv, noninteractive=True)
    service.include_launch_description(LaunchDescription(list(entities)))
    return service.run()


def user_lines(capsys) -> list[str]:
    return [line.split(': ', 1)[1] for line in capsys.readouterr().out.splitlines()
            if line.startswith('[INFO] [launch.user]')]


def say(*parts) -> LogInfo:
    return LogInfo(msg=list(parts))


def test_group_scopes(capsys):
    value = LaunchConfiguration('v', default='none')
    assert run(
        SetLaunchConfiguration('v', 'outer'),
        GroupAction([SetLaunchConfiguration('v', 'scoped'), say(value)]),
        say(value),
        GroupAction([say(value)], forwarding=False, launch_configurations={'w': 'kept'}),
        GroupAction([say(LaunchConfiguration('w'))], forwarding=False, launch_configurations={'w': 'kept'}),
        GroupAction([SetLaunchConfiguration('v', 'leaked')], scoped=False),
        say(value),
    ) == 0
    assert user_lines(capsys) == ['scoped', 'outer', 'none', 'kept', 'leaked']


def test_timer_actions_keep_the_scope_they_were_started_in(capsys):
    late = TimerAction(period=0.1, actions=[say(LaunchConfiguration('v', default='lost'))])
    assert run(GroupAction([SetLaunchConfiguration('v', 'inside'), late])) == 0
    assert user_lines(capsys) == ['inside']


def test_environment_actions_and_group_restore(capsys):
    os.environ['OWL_PATHS'] = 'b'
    env = EnvironmentVariable('OWL_PATHS', default_value='unset')
    assert run(
        AppendEnvironmentVariable('OWL_PATHS', 'c'),
        AppendEnvironmentVariable('OWL_PATHS', 'a', prepend=True, separator=':'),
        say(env),
        GroupAction([SetEnvironmentVariable('OWL_PATHS', 'group'), say(env)]),
        say(env),
        UnsetEnvironmentVariable('OWL_PATHS'),
        say(env),
    ) == 0
    assert user_lines(capsys) == ['a:b:c', 'group', 'a:b:c', 'unset']


def test_logic_substitutions_and_conditions(capsys):
    assert run(
        say(PythonExpression(['hypot(3, 4)'])),
        say(PythonExpression(['os.sep'], python_modules=['os'])),
        say(NotSubstitution('true'), ' ', EqualsSubstitution('a', 'a'), ' ',
            IfElseSubstitution('false', 'yes', 'no')),
        say(Command(['printf ', 'hello'])),
        LogInfo(msg='shown', condition=IfCondition(' TRUE ')),
        LogInfo(msg='hidden', condition=IfCondition('0')),
    ) == 0
    assert user_lines(capsys) == ['5.0', '/', 'false true no', 'hello', 'shown']


@pytest.mark.parametrize(('entity', 'message'), [
    (LogInfo(msg='x', condition=IfCondition('yes')),
     "invalid condition expression, expected one of [true, 1, false, 0] but got 'yes', expanded from "
     "''yes''"),
    (say(EnvironmentVariable('OWL_NO_SUCH_VARIABLE')),
     "environment variable 'OWL_NO_SUCH_VARIABLE' does not exist"),
    (say(Command('false')), 'executed command failed. Command: false'),
    (DeclareLaunchArgument('needed', description='a value'),
     'Required launch argument "needed" was not provided.'),
])
def test_errors_give_return_code_1_and_one_message(capsys, entity, message):
    code = run(entity, argv=[])
    out = capsys.readouterr().out
    assert code == 1
    assert f'[ERROR] [launch]: Caught exception in launch (see debug for traceback): {message}' in out


def test_argument_choices(capsys):
    choice = DeclareLaunchArgument('c', default_value='a', choices=['a', 'b'])
    assert choice.description == "One of: ['a', 'b']"
    assert run(choice, say(LaunchConfiguration('c'))) == 0
    assert user_lines(capsys) == ['a']


def test_construction_errors():
    with pytest.raises(TypeError, match="'float' object is not iterable"):
        DeclareLaunchArgument('x', default_value=1.0)
    with pytest.raises(RuntimeError, match='choices'):
        DeclareLaunchArgument('x', default_value='c', choices=['a', 'b'])
    with pytest.raises(TypeError, match='callable'):
        OpaqueFunction(function='not callable')
    with pytest.raises(TypeError, match="Failed to normalize given item of type"):
        LogInfo(msg=['a', 1])
    with pytest.raises(ValueError, match="'printer' is not a valid output destination of stdout"):
        ExecuteProcess(cmd=['true'], output={'stdout': 'printer'})


def test_executing_an_action_twice_is_an_error(capsys):
    process = ExecuteProcess(cmd=['true'])
    assert run(process, OpaqueFunction(function=lambda context: [process])) == 1
    assert "executed more than once" in capsys.readouterr().out


def test_emulate_tty_gives_the_child_a_terminal(capsys):
    check = [sys.executable, '-c', 'import sys; print(sys.stdout.isatty(), sys.stderr.isatty())']
    assert run(ExecuteProcess(cmd=check, output='screen', name='piped'),
               ExecuteProcess(cmd=check, output='screen', name='tty', emulate_tty=True)) == 0
    out = capsys.readouterr().out
    assert re.search(r'^\[piped-\d+\] False False$', out, re.MULTILINE), out
    assert re.search(r'^\[tty-\d+\] True True$', out, re.MULTILINE), out


def test_shutdown_from_another_thread():
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription([ExecuteProcess(cmd=['sleep', '60'])]))
    timer = threading.Timer(0.5, service.shutdown)
    timer.start()
    assert service.run() == 0
    timer.join()


def test_shutdown_process_and_signal_process_events(capsys):
    sleeper = ExecuteProcess(cmd=['sleep', '60'], name='sleeper')
    stubborn = ExecuteProcess(cmd=['sleep', '61'], name='signalled')
    # Each event once its process runs: an event for a process not started yet is ignored (as
    # upstream), and under load a start took longer than a fixed 0.3 s (the 'sleep 61' then ran out).
    assert run(sleeper, stubborn, RegisterEventHandler(OnProcessStart(target_action=sleeper, on_start=[
        EmitEvent(event=ShutdownProcess(process_matcher=matches_action(sleeper)))])),
        RegisterEventHandler(OnProcessStart(target_action=stubborn, on_start=[
            EmitEvent(event=SignalProcess(signal_number=signal.SIGUSR1,
                                          process_matcher=matches_action(stubborn)))]))) == 0
    out = capsys.readouterr().out
    assert re.search(r"\[INFO\] \[sleeper-\d+\]: sending signal 'SIGINT' to process\[sleeper-\d+\]", out)
    assert re.search(r"\[INFO\] \[signalled-\d+\]: sending signal 'SIGUSR1' to process\[signalled-\d+\]", out)
    assert re.search(r'process has died \[pid \d+, exit code -10, cmd .sleep 61.\]', out), out


def test_own_log_output_goes_to_files_of_the_process(tmp_path, capsys):
    assert run(ExecuteProcess(cmd=['sh', '-c', 'echo to-out; echo to-err >&2'], name='own',
                              output='own_log')) == 0
    assert 'to-out' not in capsys.readouterr().out
    [log_dir] = [p for p in (tmp_path / 'log').iterdir() if not p.is_symlink()]
    label = next(p.name for p in log_dir.iterdir() if p.name.endswith('-stdout.log'))[:-len('-stdout.log')]
    assert (log_dir / f'{label}-stdout.log').read_text().endswith(f'[{label}] to-out\n')
    assert 'to-err' in (log_dir / f'{label}-stderr.log').read_text()
    assert 'to-out' in (log_dir / f'{label}.log').read_text()
    assert (tmp_path / 'log' / 'latest').resolve() == log_dir.resolve()


def test_a_program_that_cannot_start_is_logged_not_fatal(capsys):
    assert run(ExecuteProcess(cmd=['owl_no_such_program'], output='screen')) == 0
    out = capsys.readouterr().out
    assert re.search(r"\[ERROR\] \[owl_no_such_program-\d+\]: exception occurred while executing process:\n"
                     r"FileNotFoundError: .*'owl_no_such_program'\n", out), out
    assert 'Traceback' not in out


def test_screen_and_log_formats_can_be_overridden(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv('OVERRIDE_LAUNCH_SCREEN_FORMAT', '<{levelname}> {msg}')
    monkeypatch.setenv('OVERRIDE_LAUNCH_LOG_FORMAT', 'default')
    assert run(LogInfo(msg='formatted')) == 0
    assert '<INFO> formatted' in capsys.readouterr().out.splitlines()
    assert '[INFO] [launch.user]: formatted' in (tmp_path / 'log' / 'latest' / 'launch.log').read_text()
