"""The `ros2` command (package ros2cli) against real fixture nodes over real DDS.

One ROS domain per module holds the fixture graph (talker, listener, parameter node, service
and action servers) and a warm daemon, so most checks are quick; tests that publish or need a
cold start use their own `ros` domain. Every test stops the daemons it started.
"""

import os
import re
import signal
import subprocess
import time

import pytest
from ros_harness import RosHarness

FIXTURES = 'ros2cli_test_fixtures'
FIXTURE_NODES = ['/echo_server', '/fibonacci_server', '/listener', '/parameter_node', '/talker']


def ros2(sandbox, *args, stdin=None, timeout=30.0):
    """Run `ros2 args...` to completion in the sandbox's domain; stdout and stderr apart."""
    return subprocess.run(['ros2', *args], env=sandbox.env, input=stdin, capture_output=True, text=True,
                          timeout=timeout, check=False)


def lines(result):
    return result.stdout.splitlines()


def assert_one_line_error(result, *fragments, code=1):
    """A bad input: the exit code, exactly one line on stderr naming the problem, no traceback."""
    assert result.returncode == code, (result.returncode, result.stdout, result.stderr)
    assert 'Traceback' not in result.stderr + result.stdout
    error_lines = result.stderr.strip().splitlines()
    assert len(error_lines) == 1, result.stderr
    for fragment in fragments:
        assert fragment in error_lines[0], error_lines[0]
    return error_lines[0]


def eventually(check, timeout=15.0):
    """check() until it returns a truthy value (discovery takes its time); that value."""
    deadline = time.monotonic() + timeout
    while True:
        value = check()
        if value or time.monotonic() > deadline:
            return value
        time.sleep(0.2)


def stop_daemon(sandbox):
    ros2(sandbox, 'daemon', 'stop')


@pytest.fixture(scope='module')
def graph():
    """A domain with every fixture node running and a daemon that has seen them all."""
    harness = RosHarness()
    try:
        harness.run(FIXTURES, 'talker', '--ros-args', '-p', 'rate:=5.0')
        harness.run(FIXTURES, 'listener')
        harness.run(FIXTURES, 'parameter_node')
        harness.run(FIXTURES, 'echo_server')
        harness.run(FIXTURES, 'fibonacci_server')
        assert ros2(harness, 'daemon', 'start').returncode == 0
        assert eventually(lambda: lines(ros2(harness, 'node', 'list')) == FIXTURE_NODES, 30), \
            ros2(harness, 'node', 'list').stdout
        yield harness
    finally:
        stop_daemon(harness)
        harness.close()


@pytest.fixture
def cli(ros):
    """The per-test `ros` domain, with any daemon that the test's `ros2` calls started stopped after."""
    yield ros
    stop_daemon(ros)


# ---- ros2 (top level) -------------------------------------------------------------------------

def test_help_at_every_level(graph):
    top = ros2(graph, '-h')
    assert top.returncode == 0 and 'ros2 is an extensible command-line tool for ROS 2.' in top.stdout
    for command in ('action', 'daemon', 'interface', 'node', 'param', 'run', 'service', 'topic'):
        assert f'  {command} ' in top.stdout
    bare = ros2(graph)
    assert bare.returncode == 0 and bare.stdout == top.stdout
    topic = ros2(graph, 'topic')
    assert topic.returncode == 0 and 'Call `ros2 topic <command> -h` for more detailed usage.' in topic.stdout
    verb = ros2(graph, 'topic', 'pub', '--help')
    assert verb.returncode == 0 and verb.stdout.startswith('usage: ros2 topic pub')


def test_missing_argument_is_a_usage_error(graph):
    result = ros2(graph, 'topic', 'info')
    assert result.returncode == 2
    assert 'ros2 topic info: error: the following arguments are required: topic_name' in result.stderr
    assert 'Traceback' not in result.stderr


# ---- ros2 run ---------------------------------------------------------------------------------

def test_run_passes_arguments_and_exit_code(cli):
    result = ros2(cli, 'run', FIXTURES, 'exit_code', '3', 'a b', '--ros-args', '-p', 'x:=1')
    assert result.returncode == 3
    assert "args: ['a b', '--ros-args', '-p', 'x:=1']" in result.stdout
    assert '[ros2run]: Process exited with failure 3' in result.stdout
    ok = ros2(cli, 'run', FIXTURES, 'exit_code', '0')
    assert ok.returncode == 0 and '[ros2run]' not in ok.stdout


@pytest.mark.parametrize('to_group', [True, False], ids=['group', 'ros2-pid-only'])
def test_run_delivers_sigint_to_the_child_exactly_once(cli, to_group):
    process = cli.command(['ros2', 'run', FIXTURES, 'exit_code', '5', '--wait'])
    process.wait_for('waiting for a signal')
    if to_group:
        process.send_signal(signal.SIGINT)
    else:
        os.kill(process.pid, signal.SIGINT)
    assert process.wait(10) == 5
    process.wait_for('received SIGINT$')


def test_run_unknown_executable_lists_the_package_executables(cli):
    result = ros2(cli, 'run', FIXTURES, 'talkr')
    line = assert_one_line_error(result, 'No executable found', "'talkr'", "did you mean 'talker'?")
    assert 'counter, echo_server, exit_code' in line


def test_run_unknown_package(cli):
    result = ros2(cli, 'run', 'ros2cli_test_fixturs', 'talker')
    assert_one_line_error(result, "Package 'ros2cli_test_fixturs' not found",
                          f"did you mean '{FIXTURES}'?")


# ---- ros2 node --------------------------------------------------------------------------------

def test_node_list_and_count(graph):
    assert lines(ros2(graph, 'node', 'list')) == FIXTURE_NODES
    assert lines(ros2(graph, 'node', 'list', '-c')) == [str(len(FIXTURE_NODES))]
    everything = lines(ros2(graph, 'node', 'list', '--all'))
    assert any(name.startswith('/_ros2cli_daemon_') for name in everything)


def test_node_info_sections(graph):
    result = ros2(graph, 'node', 'info', '/fibonacci_server')
    assert result.returncode == 0, result.stderr
    output = lines(result)
    assert output[:4] == ['/fibonacci_server', '  Subscribers:', '', '  Publishers:']
    assert '    /rosout: rcl_interfaces/msg/Log' in output
    assert output[-6:] == ['  Service Clients:', '', '  Action Servers:',
                           f'    /fibonacci: {FIXTURES}/action/Fibonacci', '  Action Clients:', '']
    assert result.stdout.endswith('  Action Clients:\n\n')
    assert not any('_action' in line for line in output)
    hidden = lines(ros2(graph, 'node', 'info', '/fibonacci_server', '--include-hidden'))
    assert any('/fibonacci/_action/feedback' in line for line in hidden)


def test_node_info_unknown_node(graph):
    result = ros2(graph, 'node', 'info', '/talkr')
    assert_one_line_error(result, "Unable to find node '/talkr'", "did you mean '/talker'?")


# ---- ros2 topic -------------------------------------------------------------------------------

def test_topic_list_variants(graph):
    assert lines(ros2(graph, 'topic', 'list')) == ['/chatter', '/parameter_events', '/rosout']
    assert lines(ros2(graph, 'topic', 'list', '-t')) == [
        '/chatter [std_msgs/msg/String]', '/parameter_events [rcl_interfaces/msg/ParameterEvent]',
        '/rosout [rcl_interfaces/msg/Log]']
    assert lines(ros2(graph, 'topic', 'list', '-c')) == ['3']
    verbose = lines(ros2(graph, 'topic', 'list', '-v'))
    assert verbose[:2] == ['Published topics:', ' * /chatter [std_msgs/msg/String] 1 publisher']
    assert verbose[verbose.index('Subscribed topics:') + 1] == \
        ' * /chatter [std_msgs/msg/String] 1 subscriber'
    assert verbose[-1] == ''
    hidden = lines(ros2(graph, 'topic', 'list', '--include-hidden-topics'))
    assert '/fibonacci/_action/status' in hidden


def test_topic_info_type_find(graph):
    assert lines(ros2(graph, 'topic', 'info', '/chatter')) == [
        'Type: std_msgs/msg/String', 'Publisher count: 1', 'Subscription count: 1']
    verbose = ros2(graph, 'topic', 'info', '/chatter', '-v').stdout
    assert 'Node name: talker\nNode namespace: /\nTopic type: std_msgs/msg/String\n' in verbose
    assert ('Topic type hash: RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18\n'
            'Endpoint type: PUBLISHER\n') in verbose
    assert re.search(r'GID: ([0-9a-f]{2}\.){15}[0-9a-f]{2}\nQoS profile:\n  Reliability: RELIABLE\n',
                     verbose)
    assert 'Endpoint type: SUBSCRIPTION' in verbose and '  Durability: TRANSIENT_LOCAL' in verbose
    assert '  Lifespan: Infinite\n  Deadline: Infinite\n  Liveliness: AUTOMATIC\n' in verbose
    assert lines(ros2(graph, 'topic', 'type', '/chatter')) == ['std_msgs/msg/String']
    assert lines(ros2(graph, 'topic', 'find', 'rcl_interfaces/msg/Log')) == ['/rosout']
    assert lines(ros2(graph, 'topic', 'find', '-c', 'std_msgs/msg/String')) == ['1']
    nothing = ros2(graph, 'topic', 'find', 'std_msgs/String')
    assert nothing.returncode == 0 and nothing.stdout == ''
    unknown = ros2(graph, 'topic', 'type', '/nope')
    assert unknown.returncode == 1 and unknown.stdout == unknown.stderr == ''
    hidden = ros2(graph, 'topic', 'type', '/fibonacci/_action/status')
    assert hidden.returncode == 1
    shown = ros2(graph, 'topic', 'type', '--include-hidden-topics', '/fibonacci/_action/status')
    assert lines(shown) == ['action_msgs/msg/GoalStatusArray']


def test_topic_info_unknown_topic(graph):
    result = ros2(graph, 'topic', 'info', '/chatt')
    assert_one_line_error(result, "Unknown topic '/chatt'", "did you mean '/chatter'?")


def test_topic_echo_formats(graph):
    once = ros2(graph, 'topic', 'echo', '/chatter', '--once')
    assert once.returncode == 0
    assert re.fullmatch(r"data: 'Hello World: \d+'\n---\n", once.stdout), once.stdout
    relative = ros2(graph, 'topic', 'echo', 'chatter', 'std_msgs/msg/String', '--once', '--no-str')
    assert re.fullmatch(r"data: '<string length: <\d+>>'\n---\n", relative.stdout), relative.stdout
    truncated = ros2(graph, 'topic', 'echo', '/chatter', '--once', '--truncate-length', '5')
    assert truncated.stdout == 'data: Hello...\n---\n'
    field = ros2(graph, 'topic', 'echo', '/chatter', '--once', '--field', 'data')
    assert re.fullmatch(r'Hello World: \d+\n---\n', field.stdout), field.stdout
    csv = ros2(graph, 'topic', 'echo', '/chatter', '--once', '--csv')
    assert re.fullmatch(r'Hello World: \d+\n', csv.stdout), csv.stdout
    even = ros2(graph, 'topic', 'echo', '/chatter', '--once', '--filter',
                'int(m.data.rpartition(" ")[2]) % 2 == 0')
    assert int(even.stdout.split(': ')[2].split("'")[0]) % 2 == 0


@pytest.mark.parametrize(('args', 'fragments'), [
    (['--field', 'dat'], ["Invalid field 'dat': 'String' object has no attribute 'dat'"]),
    (['--field', '.'], ["Invalid field value '.'"]),
    (['std_msgs/msg/Strin'], ['The passed message type is invalid', "did you mean 'String'?"]),
    (['--filter', 'm.data ==='], ["Invalid filter expression 'm.data ==='"]),
])
def test_topic_echo_bad_input(graph, args, fragments):
    assert_one_line_error(ros2(graph, 'topic', 'echo', '/chatter', *args, '--once'), *fragments)


def test_topic_echo_unknown_topic(graph):
    result = ros2(graph, 'topic', 'echo', '/chatt')
    assert 'WARNING: topic [/chatt] does not appear to be published yet' in result.stdout
    assert_one_line_error(result, 'Could not determine the type for the passed topic',
                          "did you mean '/chatter'?")


def test_topic_pub_times_exact_output(cli):
    result = ros2(cli, 'topic', 'pub', '-t', '3', '-w', '0', '-r', '20', '/t', 'std_msgs/String',
                  'data: hello')
    assert result.returncode == 0, result.stderr
    assert result.stdout == 'publisher: beginning loop\n' + ''.join(
        f"publishing #{n}: std_msgs.msg.String(data='hello')\n\n" for n in (1, 2, 3))


def test_topic_pub_once_reaches_a_listener(cli):
    listener = cli.run(FIXTURES, 'listener', '--ros-args', '-r', 'chatter:=/chit_chatter')
    result = ros2(cli, 'topic', 'pub', '-1', '--qos-durability', 'transient_local', '--qos-reliability',
                  'reliable', '/chit_chatter', 'std_msgs/msg/String', '{data: foo}')
    assert result.returncode == 0, result.stderr
    assert lines(result)[:2] == ['publisher: beginning loop',
                                 "publishing #1: std_msgs.msg.String(data='foo')"]
    listener.wait_for(r'\[listener\]: I heard: \[foo\]')


def test_topic_pub_course_command_and_echo(cli):
    echo = cli.command(['ros2', 'topic', 'echo', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist'])
    pub = cli.command(['ros2', 'topic', 'pub', '-r', '5', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist',
                       '{linear: {x: 2}, angular: {z: 1.8}}'])
    echo.wait_for('^---$', timeout=20)
    block = echo.lines[echo.lines.index('---') - 8:echo.lines.index('---') + 1]
    assert block == ['linear:', '  x: 2.0', '  y: 0.0', '  z: 0.0', 'angular:', '  x: 0.0', '  y: 0.0',
                     '  z: 1.8', '---']
    pub.wait_for(r'^publishing #2: geometry_msgs\.msg\.Twist\(linear=geometry_msgs\.msg\.Vector3\(x=2\.0, '
                 r'y=0\.0, z=0\.0\), angular=geometry_msgs\.msg\.Vector3\(x=0\.0, y=0\.0, z=1\.8\)\)$')
    assert pub.stop() in (0, 2) and echo.stop() in (0, 2)
    assert 'Traceback' not in pub.output + echo.output


def test_topic_pub_waits_then_times_out(cli):
    result = ros2(cli, 'topic', 'pub', '-t', '5', '--max-wait-time-secs', '1', '/nobody', 'std_msgs/String')
    assert lines(result) == ['Waiting for at least 1 matching subscription(s)...'] * 2
    assert_one_line_error(result, 'Timed out waiting for subscribers: Expected 1 subcribers but only got 0 '
                                  'subscribers')
    alone = ros2(cli, 'topic', 'pub', '--max-wait-time-secs', '1', '/nobody', 'std_msgs/String')
    assert_one_line_error(alone, '--max-wait-time-secs option is only effective with')


@pytest.mark.parametrize(('message_type', 'values', 'fragments'), [
    ('geometry_msgs/msg/Twist', '{linear: {x: 1}', ['Failed to populate field: invalid YAML']),
    ('geometry_msgs/msg/Twist', '{linaer: {x: 1}}', ["unknown field 'linaer'", "did you mean 'linear'?"]),
    ('geometry_msgs/msg/Twist', '{linear: {x: fast}}', ["field 'linear.x' expects a number", "'fast'"]),
    ('geometry_msgs/msg/Twist', '{linear: 3}', ["field 'linear' must be a mapping"]),
    ('std_msgs/msg/UInt8', '{data: 300}', ["field 'data' expects a uint8 in [0, 255], got 300"]),
    ('std_msgs/msg/Bool', '{data: maybe}', ["field 'data' expects a boolean"]),
    ('geometry_msgs/msg/Twist', '[1, 2]', ['The passed value needs to be a dictionary in YAML format']),
    ('geometry_msgs/msg/Twst', '{}', ['The passed message type is invalid', "did you mean 'Twist'?"]),
    ('geometri_msgs/msg/Twist', '{}', ["unknown package 'geometri_msgs'", "did you mean 'geometry_msgs'?"]),
    ('Twist', '{}', ['The passed message type is invalid', "'Twist' is not a message type name"]),
])
def test_topic_pub_bad_input(cli, message_type, values, fragments):
    result = ros2(cli, 'topic', 'pub', '-1', '/t', message_type, values)
    assert_one_line_error(result, *fragments)
    assert 'publisher: beginning loop' not in result.stdout


def test_topic_hz_and_bw(graph):
    hz = graph.command(['ros2', 'topic', 'hz', '/chatter'])
    match = hz.wait_for(r'^average rate: (\d+\.\d{3})$', timeout=20)[0]
    assert 4.0 < float(match.group(1)) < 6.0
    hz.wait_for(r'^\tmin: \d+\.\d{3}s max: \d+\.\d{3}s std dev: \d+\.\d{5}s window: \d+$')
    bw = graph.command(['ros2', 'topic', 'bw', '/chatter'])
    bw.wait_for(r'^Subscribed to \[/chatter\]$', timeout=20)
    bw.wait_for(r'^\d+ B/s from \d+ messages$', timeout=20)
    bw.wait_for(r'^\tMessage size mean: \d+ B min: \d+ B max: \d+ B$')
    assert hz.stop() == 2 and bw.stop() == 2
    assert 'Traceback' not in hz.output + bw.output


# ---- ros2 interface ---------------------------------------------------------------------------

def test_interface_show_twist_as_upstream(graph):
    result = ros2(graph, 'interface', 'show', 'geometry_msgs/msg/Twist')
    assert result.stdout == (
        '# This expresses velocity in free space broken into its linear and angular parts.\n\n'
        'Vector3  linear\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n'
        'Vector3  angular\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n')


def test_interface_show_nesting_and_comment_modes(graph):
    default = lines(ros2(graph, 'interface', 'show', f'{FIXTURES}/msg/Tree'))
    assert default == [
        '# The outermost type of the nesting fixtures',
        'Branch branch # Comment at level 3',
        '\tLeaf leaf',
        '\t\tbool GREEN=true',
        '\t\tbool wilted',
        '\t\tint32[<=3] veins',
        'string name',
        '# Trailing comment of Tree']
    everything = lines(ros2(graph, 'interface', 'show', '--all-comments', f'{FIXTURES}/msg/Tree'))
    assert everything == [
        '# The outermost type of the nesting fixtures',
        'Branch branch # Comment at level 3',
        '\t# Holds one leaf',
        '\tLeaf leaf # Comment at level 2',
        '\t\t# The innermost type of the nesting fixtures',
        '',
        '\t\t# A constant, then fields',
        '\t\tbool GREEN=true # Comment at level 1',
        '\t\tbool wilted',
        '\t\tint32[<=3] veins # bounded sequence, level 1',
        '',
        '\t\t# Trailing comment of Leaf',
        '\t# Trailing comment of Branch',
        'string name',
        '# Trailing comment of Tree']
    bare = lines(ros2(graph, 'interface', 'show', '--no-comments', f'{FIXTURES}/msg/Tree'))
    assert bare == ['Branch branch', '\tLeaf leaf', '\t\tbool GREEN=true', '\t\tbool wilted',
                    '\t\tint32[<=3] veins', 'string name']
    action = lines(ros2(graph, 'interface', 'show', f'{FIXTURES}/action/Fibonacci'))
    assert action == ['# Goal: how many elements', 'int32 order', '---', '# Result: the whole sequence',
                      'int32[] sequence', '---', '# Feedback: the sequence so far', 'int32[] sequence']
    piped = ros2(graph, 'interface', 'show', '-', stdin='std_srvs/srv/SetBool\n')
    assert lines(piped)[0] == 'bool data # e.g. for hardware enabling / disabling' and '---' in lines(piped)


@pytest.mark.parametrize(('name', 'fragments'), [
    ('geometri_msgs/msg/Twist', ["Unknown package 'geometri_msgs'", "did you mean 'geometry_msgs'?"]),
    ('geometry_msgs/msg/Twst', ["Could not find the interface '", "Twst.idl'", "did you mean 'Twist'?"]),
    ('geometry_msgs/Twist', ["Invalid name 'geometry_msgs/Twist'. Expected three parts separated by '/'"]),
])
def test_interface_show_bad_names(graph, name, fragments):
    assert_one_line_error(ros2(graph, 'interface', 'show', name), *fragments)


def test_interface_list_package_packages_proto(graph):
    listing = lines(ros2(graph, 'interface', 'list'))
    assert listing[0] == 'Messages:' and 'Services:' in listing and 'Actions:' in listing
    assert f'    {FIXTURES}/action/Fibonacci' in listing and '    std_srvs/srv/SetBool' in listing
    only_actions = lines(ros2(graph, 'interface', 'list', '-a'))
    assert only_actions[0] == 'Actions:' and all('/action/' in line for line in only_actions[1:])
    assert lines(ros2(graph, 'interface', 'package', FIXTURES)) == [
        f'{FIXTURES}/msg/Branch', f'{FIXTURES}/msg/Leaf', f'{FIXTURES}/msg/Tree',
        f'{FIXTURES}/action/Fibonacci']
    assert lines(ros2(graph, 'interface', 'package', '-a', FIXTURES)) == [f'{FIXTURES}/action/Fibonacci']
    assert_one_line_error(ros2(graph, 'interface', 'package', 'std_srv'), "Unknown package 'std_srv'",
                          "did you mean 'std_srvs'?")
    packages = lines(ros2(graph, 'interface', 'packages', '-s'))
    assert 'std_srvs' in packages and 'std_msgs' not in packages
    assert ros2(graph, 'interface', 'proto', 'std_msgs/msg/String').stdout == '"data: \'\'\n"\n'
    assert ros2(graph, 'interface', 'proto', '--no-quotes', f'{FIXTURES}/action/Fibonacci').stdout == \
        'order: 0\n\n'


def test_no_daemon_gives_the_same_answers(graph):
    for args in (['node', 'list'], ['topic', 'list', '-t'], ['node', 'info', '/talker'],
                 ['topic', 'info', '/chatter']):
        warm = ros2(graph, *args)
        assert warm.returncode == 0
        cold = lambda args=args: ros2(graph, *args, '--no-daemon').stdout  # noqa: E731
        assert eventually(lambda cold=cold, warm=warm: cold() == warm.stdout), args


def test_daemon_start_stop_status(cli):
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is not running']
    assert lines(ros2(cli, 'daemon', 'stop')) == ['The daemon is not running']
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon has been started']
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon is already running']
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is running']
    assert lines(ros2(cli, 'daemon', 'stop')) == ['The daemon has been stopped']
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is not running']


def test_first_call_without_daemon_starts_one(cli):
    assert ros2(cli, 'node', 'list').returncode == 0
    assert eventually(lambda: lines(ros2(cli, 'daemon', 'status')) == ['The daemon is running'], 10)
    assert ros2(cli, 'node', 'list', '--no-daemon').returncode == 0

