"""The `ros2` command (package ros2cli) against real fixture nodes over real DDS.

One ROS domain per module holds the fixture graph (talker, listener, parameter node, service
and action servers) and a warm daemon, so most checks are quick; tests that publish or need a
cold start use their own `ros` domain. Every test stops the daemons it started.
"""

import contextlib
import io
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import pytest
from owl_common.graph import GraphQueries
from ros2cli.cli import main as ros2_main
from ros_harness import RosHarness, with_hung_teardown

FIXTURES = 'ros2cli_test_fixtures'
FIXTURE_NODES = ['/echo_server', '/fibonacci_server', '/listener', '/mutable_params', '/parameter_node',
                 '/talker']


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


def ros2_at_once(sandbox, *calls):
    """Run several `ros2` calls side by side (each a tuple of args); their results in that order.

    For calls that mostly wait (for discovery, a message, a timeout) and need nothing of each other.
    """
    with ThreadPoolExecutor(max_workers=len(calls)) as pool:
        return list(pool.map(lambda args: ros2(sandbox, *args), calls))


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
        harness.run(FIXTURES, 'parameter_node', '--ros-args', '-r', '__node:=mutable_params')
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
    assert top.returncode == 0
    assert 'ros2 is an extensible command-line tool for ROS 2.' in top.stdout
    assert top.stdout.endswith('Commands:\n  action            Various action related sub-commands\n'
                               '  bag               Various rosbag related sub-commands\n'
                               '  daemon            Various daemon related sub-commands\n'
                               '  doctor            Check ROS setup and other potential issues\n'
                               '  extension_points  List extension points\n'
                               '  extensions        List extensions\n'
                               '  interface         Show information about ROS interfaces\n'
                               '  launch            Run a launch file\n'
                               '  node              Various node related sub-commands\n'
                               '  param             Various param related sub-commands\n'
                               '  pkg               Various package related sub-commands\n'
                               '  run               Run a package specific executable\n'
                               '  service           Various service related sub-commands\n'
                               '  topic             Various topic related sub-commands\n'
                               '  wtf               Use `wtf` as alias to `doctor`\n\n'
                               '  Call `ros2 <command> -h` for more detailed usage.\n')
    bare = ros2(graph)
    assert bare.returncode == 0
    assert bare.stdout == top.stdout
    for command in ('action', 'daemon', 'doctor', 'interface', 'node', 'param', 'service', 'topic'):
        assert ros2_in_process(command, '-h')[1].startswith(f'usage: ros2 {command}')
    topic = ros2(graph, 'topic')
    assert topic.returncode == 0
    assert '\n  bw    Display bandwidth used by topic\n  echo  Output messages from a topic\n' in topic.stdout
    assert topic.stdout.endswith('\n\n  Call `ros2 topic <command> -h` for more detailed usage.\n')
    verbs = {'action': ['info', 'list', 'send_goal', 'type'], 'daemon': ['start', 'status', 'stop'],
             'interface': ['list', 'package', 'packages', 'proto', 'show'], 'node': ['info', 'list'],
             'param': ['delete', 'describe', 'dump', 'get', 'list', 'load', 'set'],
             'service': ['call', 'find', 'list', 'type'],
             'topic': ['bw', 'echo', 'find', 'hz', 'info', 'list', 'pub', 'type']}
    for command, names in verbs.items():  # the same parser in this process: help needs no ROS
        for name in names:
            code, text = ros2_in_process(command, name, '--help')
            assert code == 0, text
            assert text.startswith(f'usage: ros2 {command} {name}'), text
    assert ros2_in_process('run', '-h')[1].startswith('usage: ros2 run [-h] [--prefix PREFIX]')


def ros2_in_process(*argv: str) -> tuple[int, str]:
    """The exit code and output of `ros2 argv` that argparse ends (help, usage), run in this process."""
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), pytest.raises(SystemExit) as ended:
        ros2_main(list(argv))
    return int(ended.value.code or 0), printed.getvalue()


def test_missing_argument_is_a_usage_error(graph):
    result = ros2(graph, 'topic', 'info')
    assert result.returncode == 2
    assert 'ros2 topic info: error: the following arguments are required: topic_name' in result.stderr
    assert 'Traceback' not in result.stderr


# Runs an installed `ros2` (argv[1:]) as its console script does, with an at-exit handler and an
# object that says when the interpreter is finalized (module globals are deleted then).
EXIT_PROBE = """
import atexit, runpy, sys
class Finalized:
    def __del__(self):
        print('interpreter finalized', flush=True)
finalized = Finalized()
atexit.register(print, 'at-exit handlers ran')
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name='__main__')
"""


def test_ros2_skips_static_clean_up_once_its_participant_is_gone(cli):
    # Fast DDS's factory sleeps 100 ms in its static destructor; console_main leaves with os._exit
    # instead, after the at-exit handlers (coverage's among them) and with stdout flushed.
    executable = shutil.which('ros2', path=cli.env['PATH'])
    assert executable is not None
    result = subprocess.run([sys.executable, '-c', EXIT_PROBE, executable, '--use-python-default-buffering',
                             'topic', 'list', '--no-daemon', '--spin-time', '0'],
                            env=cli.env, capture_output=True, text=True, timeout=30, check=False)
    assert result.returncode == 0, result
    assert result.stdout.splitlines() == ['/parameter_events', '/rosout', 'at-exit handlers ran'], result
    assert 'interpreter finalized' not in result.stdout
    # A verb that fails once its node is made (one that looks for a name fails only after its
    # discovery grace, NAMED_LOOKUP_GRACE).
    failed = subprocess.run([sys.executable, '-c', EXIT_PROBE, executable, 'topic', 'echo', '/nowhere',
                             'std_msgs/msg/Nowhere', '--spin-time', '0'],
                            env=cli.env, capture_output=True, text=True, timeout=30, check=False)
    assert_one_line_error(failed, 'The passed message type is invalid', 'Nowhere')
    assert failed.stdout.splitlines() == ['at-exit handlers ran']


# The decision, after rclpy has been initialized and with a thread still working, and after both end.
EXIT_DECISION = """
import threading, rclpy
from ros2cli.cli import can_end_without_static_cleanup
print('before init', can_end_without_static_cleanup())
rclpy.init()
print('initialized', can_end_without_static_cleanup())
rclpy.shutdown()
release = threading.Event()
worker = threading.Thread(target=release.wait)
worker.start()
print('worker running', can_end_without_static_cleanup())
release.set()
worker.join()
print('all done', can_end_without_static_cleanup())
"""


def test_ros2_takes_the_ordinary_exit_while_a_participant_or_a_thread_is_left(cli):
    result = subprocess.run([sys.executable, '-c', EXIT_DECISION], env=cli.env, capture_output=True,
                            text=True, timeout=30, check=False)
    assert result.returncode == 0, result
    assert result.stdout.splitlines() == ['before init True', 'initialized False', 'worker running False',
                                          'all done True']


# The clean-up watchdog's limit in the runs below, instead of owl_common.run.TEARDOWN_LIMIT's 5 s:
# begin_cleanup() reads the module's value when it arms the watchdog, so the hang ends after this
# long, still by that watchdog (without it these runs hang for a minute).
HUNG_TEARDOWN_LIMIT = 1
SHORTER_TEARDOWN_LIMIT = f'import owl_common.run\nowl_common.run.TEARDOWN_LIMIT = {HUNG_TEARDOWN_LIMIT}\n'


def hung_ros2(sandbox, *args):
    """`ros2 args...` whose clean-up hangs as in a Fast DDS teardown deadlock (see with_hung_teardown).

    Its watchdog's limit is HUNG_TEARDOWN_LIMIT.
    """
    executable = shutil.which('ros2', path=sandbox.env['PATH'])
    assert executable is not None
    python, option, code, *rest = with_hung_teardown(executable, *args)
    return sandbox.command([python, option, SHORTER_TEARDOWN_LIMIT + code, *rest], label='ros2')


def test_a_verb_whose_clean_up_hangs_ends_itself_with_every_stack(cli):
    pub = hung_ros2(cli, 'topic', 'pub', '-w', '0', '/t', 'std_msgs/msg/String', 'data: hello')
    pub.wait_for('publishing #1', timeout=30)
    pub.send_signal(signal.SIGINT)
    assert pub.wait(timeout=HUNG_TEARDOWN_LIMIT + 3) == 1, pub.tail()
    assert f'Timeout (0:00:0{HUNG_TEARDOWN_LIMIT})!' in pub.output, pub.tail()
    assert 'in destroy_node' in pub.output, pub.tail()


def test_a_verb_stopped_before_it_could_clean_up_cannot_hang_at_exit(cli):
    listing = hung_ros2(cli, 'topic', 'list', '--no-daemon', '--spin-time', '60')
    # Still in its discovery spin: Ctrl-C leaves the node to interpreter exit.
    assert eventually(lambda: any(name.startswith('_ros2cli_') for name in cli.probe.node.get_node_names()))
    listing.send_signal(signal.SIGINT)
    assert listing.wait(timeout=HUNG_TEARDOWN_LIMIT + 3) == 1, listing.tail()
    assert f'Timeout (0:00:0{HUNG_TEARDOWN_LIMIT})!' in listing.output, listing.tail()


# ---- ros2 run ---------------------------------------------------------------------------------

def test_run_passes_arguments_and_exit_code(cli):
    result = ros2(cli, 'run', FIXTURES, 'exit_code', '3', 'a b', '--ros-args', '-p', 'x:=1')
    assert result.returncode == 3
    assert "args: ['a b', '--ros-args', '-p', 'x:=1']" in result.stdout
    assert '[ros2run]: Process exited with failure 3' in result.stdout
    ok = ros2(cli, 'run', FIXTURES, 'exit_code', '0')
    assert ok.returncode == 0
    assert '[ros2run]' not in ok.stdout


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


def test_run_prefix(cli):
    result = ros2(cli, 'run', '--prefix', 'echo prefixed', FIXTURES, 'exit_code', '4')
    assert result.returncode == 0
    assert re.fullmatch(r'prefixed \S+/lib/ros2cli_test_fixtures/exit_code 4\n', result.stdout), result.stdout


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


def test_duplicate_node_names_are_reported(cli):
    cli.run(FIXTURES, 'talker')
    cli.run(FIXTURES, 'talker')
    assert eventually(lambda: lines(ros2(cli, 'node', 'list')) == ['/talker', '/talker'], 30)
    listing = ros2(cli, 'node', 'list')
    assert listing.stderr == ('WARNING: Be aware that there are nodes in the graph that share an exact name, '
                              'which can have unintended side effects.\n')
    info = ros2(cli, 'node', 'info', '/talker')
    assert info.returncode == 0
    assert lines(info)[0] == '/talker'
    assert info.stderr == ('There are 2 nodes in the graph with the exact name "/talker". '
                           'You are seeing information about only one of them.\n')


def test_a_node_that_left_the_graph_has_nothing_to_show(ros):
    # A verb lists the nodes, then asks about each one: a node that ends in between (another `ros2`
    # process's own node, under a busy suite) made `ros2 action info` fail with "RCLError: Failed to
    # get action client names and type". Such a node now has nothing to show; one that is there
    # still shows what it has. (A domain of its own: a probe in `graph` would be one node too many
    # for the tests that list it.)
    ros.run(FIXTURES, 'fibonacci_server')
    queries = GraphQueries(ros.probe.node)
    for query in (queries.publishers_by_node, queries.subscribers_by_node, queries.services_by_node,
                  queries.clients_by_node, queries.action_servers_by_node, queries.action_clients_by_node):
        assert query('left_already', '/') == [], query.__name__
    ros.probe.wait_for_node('fibonacci_server', 30)
    assert eventually(lambda: queries.action_servers_by_node('fibonacci_server', '/'), 10) == [
        ['/fibonacci', ['ros2cli_test_fixtures/action/Fibonacci']]]


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
    assert 'Endpoint type: SUBSCRIPTION' in verbose
    assert '  Durability: TRANSIENT_LOCAL' in verbose
    assert '  Lifespan: Infinite\n  Deadline: Infinite\n  Liveliness: AUTOMATIC\n' in verbose
    assert lines(ros2(graph, 'topic', 'type', '/chatter')) == ['std_msgs/msg/String']
    assert lines(ros2(graph, 'topic', 'find', 'rcl_interfaces/msg/Log')) == ['/rosout']
    assert lines(ros2(graph, 'topic', 'find', '-c', 'std_msgs/msg/String')) == ['1']
    nothing = ros2(graph, 'topic', 'find', 'std_msgs/String')
    assert nothing.returncode == 0
    assert nothing.stdout == ''
    unknown = ros2(graph, 'topic', 'type', '/nope')
    assert unknown.returncode == 1
    assert unknown.stdout == unknown.stderr == ''
    hidden = ros2(graph, 'topic', 'type', '/fibonacci/_action/status')
    assert hidden.returncode == 1
    shown = ros2(graph, 'topic', 'type', '--include-hidden-topics', '/fibonacci/_action/status')
    assert lines(shown) == ['action_msgs/msg/GoalStatusArray']


def test_topic_info_unknown_topic(graph):
    result = ros2(graph, 'topic', 'info', '/chatt')
    assert_one_line_error(result, "Unknown topic '/chatt'", "did you mean '/chatter'?")


def test_topic_echo_formats(graph):
    once, relative, truncated, field, csv, even = ros2_at_once(
        graph, ('topic', 'echo', '/chatter', '--once'),
        ('topic', 'echo', 'chatter', 'std_msgs/msg/String', '--once', '--no-str'),
        ('topic', 'echo', '/chatter', '--once', '--truncate-length', '5'),
        ('topic', 'echo', '/chatter', '--once', '--field', 'data'),
        ('topic', 'echo', '/chatter', '--once', '--csv'),
        ('topic', 'echo', '/chatter', '--once', '--filter', 'int(m.data.rpartition(" ")[2]) % 2 == 0'))
    assert once.returncode == 0
    assert re.fullmatch(r"data: 'Hello World: \d+'\n---\n", once.stdout), once.stdout
    assert re.fullmatch(r"data: '<string length: <\d+>>'\n---\n", relative.stdout), relative.stdout
    assert truncated.stdout == 'data: Hello...\n---\n'
    assert re.fullmatch(r'Hello World: \d+\n---\n', field.stdout), field.stdout
    assert re.fullmatch(r'Hello World: \d+\n', csv.stdout), csv.stdout
    assert int(even.stdout.split(': ')[2].split("'")[0]) % 2 == 0


def test_topic_echo_incompatible_qos_and_stdin_values(graph):
    echo = graph.command(['ros2', 'topic', 'echo', '--qos-durability', 'transient_local', '--qos-reliability',
                          'reliable', '/chatter'])
    call = ros2(graph, 'service', 'call', '--stdin', '/echo', 'std_srvs/srv/SetBool', stdin='data: true\n')
    assert "std_srvs.srv.SetBool_Response(success=True, message='received True')" in call.stdout
    echo.wait_for("New publisher discovered on topic '/chatter', offering incompatible QoS.", timeout=20)
    assert echo.stop() == 2


def test_topic_echo_raw_info_timeout(graph):
    raw, info, quiet = ros2_at_once(graph, ('topic', 'echo', '/chatter', '--once', '--raw'),
                                    ('topic', 'echo', '/chatter', '--once', '-i'),
                                    ('topic', 'echo', '--timeout', '1', '/quiet', 'std_msgs/msg/String'))
    assert re.fullmatch(r"b'\\x00\\x01\\x00\\x00.*Hello World: \d+\\x00.*'\n---\n", raw.stdout), raw.stdout
    assert re.match(r'publication_sequence_number: \d+\nreceived_timestamp: \d+\n'
                    r'reception_sequence_number: (\d+|null)\nsource_timestamp: \d+\n---\ndata: ',
                    info.stdout), info.stdout
    assert quiet.returncode == 0
    assert quiet.stdout == ''


def test_topic_echo_no_arr_and_lossless_burst(cli):
    echo = cli.command(['ros2', 'topic', 'echo', '--no-arr', '/imu', 'sensor_msgs/msg/Imu'])
    # The counter's own policies: a late-matching echo still gets the first messages of the burst.
    counts = cli.command(['ros2', 'topic', 'echo', '--qos-reliability', 'reliable', '--qos-durability',
                          'transient_local', '--qos-depth', '1000', '--field', 'data', '/burst',
                          'std_msgs/msg/Int32'])
    cli.command(['ros2', 'topic', 'pub', '-r', '5', '/imu', 'sensor_msgs/msg/Imu', '{header: auto}'])
    echo.wait_for("^orientation_covariance: '<array type: double\\[9\\]>'$", timeout=20)
    counter = cli.run(FIXTURES, 'counter', '--ros-args', '-p', 'rate:=1000.0', '-p', 'limit:=500',
                      '-p', 'wait_for:=1', '-r', 'count:=/burst')
    counter.wait_for('published 500 messages', timeout=30)
    counts.wait_for('^500$', timeout=10)
    assert [int(line) for line in counts.lines if line.isdigit()] == list(range(1, 501))


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
    # -1 waits for the listener to match, saying so each second until it does (as upstream).
    printed = [line for line in lines(result) if line != 'Waiting for at least 1 matching subscription(s)...']
    assert printed[:2] == ['publisher: beginning loop', "publishing #1: std_msgs.msg.String(data='foo')"]
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
    assert pub.stop() in (0, 2)
    assert echo.stop() in (0, 2)
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


@pytest.mark.parametrize(('args', 'fragments'), [
    (['topic', 'pub', '-1', '/bad name', 'std_msgs/msg/String'], ['Invalid topic name', "'/bad name'"]),
    (['topic', 'pub', '-1', '-n', 'bad name', '/t', 'std_msgs/msg/String'],
     ['Invalid node name', "'bad name'"]),
    (['service', 'call', 'bad name', 'std_srvs/srv/SetBool'], ['Invalid service name', "'/bad name'"]),
])
def test_invalid_names_are_one_line(cli, args, fragments):
    line = assert_one_line_error(ros2(cli, *args), *fragments)
    assert '.c:' not in line


@pytest.mark.parametrize(('domain', 'args'), [
    ('300', ['topic', 'list']),                  # through the daemon: not domain 0's graph instead
    ('abc', ['node', 'list', '--no-daemon']),    # a node of its own: not Fast DDS's log lines
])
def test_a_domain_no_node_can_use_is_one_line(domain, args):
    result = subprocess.run(['ros2', *args], env={**os.environ, 'ROS_DOMAIN_ID': domain},
                            capture_output=True, text=True, timeout=30, check=False)
    expected = f"ros2: ROS_DOMAIN_ID is '{domain}'; it must be a number from 0 to 232"
    assert assert_one_line_error(result, expected) == expected
    assert result.stdout == ''  # nothing of another domain


def test_topic_hz_and_bw(graph):
    # All three at once: each mostly waits (for its once-a-second reports, or its grace period).
    hz = graph.command(['ros2', 'topic', 'hz', '/chatter'])
    bw = graph.command(['ros2', 'topic', 'bw', '/chatter'])
    mistyped = graph.command(['ros2', 'topic', 'hz', '/chatt'])
    # The third report averages ~3 s of a 5 Hz talker, so one late message on a loaded machine
    # does not decide it; the bounds only say hz counts what arrives (bench/ros2cli_graph.py
    # measures its accuracy).
    match = hz.wait_for(r'^average rate: (\d+\.\d{3})$', timeout=20, count=3)[-1]
    assert 3.0 < float(match.group(1)) < 7.0
    hz.wait_for(r'^\tmin: \d+\.\d{3}s max: \d+\.\d{3}s std dev: \d+\.\d{5}s window: \d+$')
    bw.wait_for(r'^Subscribed to \[/chatter\]$', timeout=20)
    bw.wait_for(r'^\d+ B/s from \d+ messages$', timeout=20)
    bw.wait_for(r'^\tMessage size mean: \d+ B min: \d+ B max: \d+ B$')
    assert hz.stop() == 2
    assert bw.stop() == 2
    assert 'Traceback' not in hz.output + bw.output
    mistyped.wait_for(r'^WARNING: topic \[/chatt\] does not appear to be published yet$')
    mistyped.wait_for("No topic '/chatt' yet \\(did you mean '/chatter'\\?\\); still waiting", timeout=20)
    assert mistyped.stop() == 2


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
    assert lines(piped)[0] == 'bool data # e.g. for hardware enabling / disabling'
    assert '---' in lines(piped)


@pytest.mark.parametrize(('name', 'fragments'), [
    ('geometri_msgs/msg/Twist', ["Unknown package 'geometri_msgs'", "did you mean 'geometry_msgs'?"]),
    ('geometry_msgs/msg/Twst', ["Could not find the interface '", "Twst.idl'", "did you mean 'Twist'?"]),
    ('geometry_msgs/Twist', ["Invalid name 'geometry_msgs/Twist'. Expected three parts separated by '/'"]),
])
def test_interface_show_bad_names(graph, name, fragments):
    assert_one_line_error(ros2(graph, 'interface', 'show', name), *fragments)


def test_interface_list_package_packages_proto(graph):
    listing = lines(ros2(graph, 'interface', 'list'))
    assert listing[0] == 'Messages:'
    assert 'Services:' in listing
    assert 'Actions:' in listing
    assert f'    {FIXTURES}/action/Fibonacci' in listing
    assert '    std_srvs/srv/SetBool' in listing
    only_actions = lines(ros2(graph, 'interface', 'list', '-a'))
    assert only_actions[0] == 'Actions:'
    assert all('/action/' in line for line in only_actions[1:])
    assert lines(ros2(graph, 'interface', 'package', FIXTURES)) == [
        f'{FIXTURES}/msg/Branch', f'{FIXTURES}/msg/Leaf', f'{FIXTURES}/msg/Tree',
        f'{FIXTURES}/action/Fibonacci']
    assert lines(ros2(graph, 'interface', 'package', '-a', FIXTURES)) == [f'{FIXTURES}/action/Fibonacci']
    assert_one_line_error(ros2(graph, 'interface', 'package', 'std_srv'), "Unknown package 'std_srv'",
                          "did you mean 'std_srvs'?")
    packages = lines(ros2(graph, 'interface', 'packages', '-s'))
    assert 'std_srvs' in packages
    assert 'std_msgs' not in packages
    assert ros2(graph, 'interface', 'proto', 'std_msgs/msg/String').stdout == '"data: \'\'\n"\n'
    assert ros2(graph, 'interface', 'proto', '--no-quotes', f'{FIXTURES}/action/Fibonacci').stdout == \
        'order: 0\n\n'


def test_no_daemon_gives_the_same_answers(graph):
    def agree(args):
        answers: list[str] = []

        def same():
            # Both sides again each time: the daemon keeps a node that died without saying goodbye
            # until its lease expires, a daemon-less run never sees it.
            warm = ros2(graph, *args)
            assert warm.returncode == 0
            # The daemon-less verb waits for discovery as a user's does (until every participant of
            # this machine is seen: ros2cli.node.settle). Should an announcement come later than
            # that with both cores busy, the next try has it: this test is about what the answers
            # say, not how fast discovery is.
            answers[:] = [warm.stdout, ros2(graph, *args, '--no-daemon').stdout]
            return answers[0] == answers[1]

        return eventually(same), args, answers

    verbs = (['node', 'list'], ['topic', 'list', '-t'], ['node', 'info', '/talker'],
             ['topic', 'info', '/chatter'], ['service', 'list', '-t'], ['action', 'list', '-t'],
             ['action', 'info', '/fibonacci'], ['param', 'get', '/parameter_node', 'str_param'],
             ['param', 'dump', '/parameter_node'])
    # Five verbs at a time: each mostly waits, for discovery or for the daemon (more at once only
    # wait for each other's start on two cores).
    with ThreadPoolExecutor(max_workers=5) as pool:
        for agreed, args, answers in pool.map(agree, verbs):
            assert agreed, (args, answers)


def test_daemon_start_stop_status(cli):
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is not running']
    assert lines(ros2(cli, 'daemon', 'stop')) == ['The daemon is not running']
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon has been started']
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon is already running']
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is running']
    assert lines(ros2(cli, 'daemon', 'stop')) == ['The daemon has been stopped']
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is not running']


# Our client's JSON calls beside upstream's XML-RPC, good and bad ones.
DAEMON_CALLS = r'''
import json, socket, sys, xmlrpc.client
port = int(sys.argv[1])

def post(path, body, length=None):
    with socket.create_connection(('127.0.0.1', port), timeout=10) as connection:
        length = len(body) if length is None else length
        connection.sendall(b'POST %s HTTP/1.0\r\nContent-Length: %d\r\n\r\n' % (path.encode(), length) + body)
        reply = b''
        while chunk := connection.recv(65536):
            reply += chunk
    head, _, payload = reply.partition(b'\r\n\r\n')
    return head.split()[1].decode(), payload.decode(errors='replace')

for body in (b'{"method": "get_domain_id", "params": []}', b'not json', b'[1, 2]',
             b'{"method": "get_domain_id", "params": {"a": 1}}', b'{"method": "no_such_call", "params": []}',
             b'{"method": "get_domain_id", "params": [1, 2]}'):
    status, payload = post('/ros2cli/json', body)
    refused = 'error page' if 'expected a JSON object' in payload else payload
    print(status, json.loads(payload) if status == '200' else refused)
print(post('/ros2cli/json', b'{"method": "get_domain_id", "params": []}', length=-5)[0])
print('xml-rpc', xmlrpc.client.ServerProxy(f'http://127.0.0.1:{port}/ros2cli/').get_domain_id())
'''


def test_the_daemon_answers_json_and_xml_rpc_calls_and_refuses_bad_ones(cli):
    from owl_common.processes import ROS2_DAEMON_BASE_PORT
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon has been started']
    done = subprocess.run([sys.executable, '-c', DAEMON_CALLS, str(ROS2_DAEMON_BASE_PORT + cli.domain_id)],
                          env=cli.env, capture_output=True, text=True, timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    answers = lines(done)
    assert answers[:4] == [f"200 {{'result': {cli.domain_id}}}", '400 error page', '400 error page',
                           '400 error page'], answers
    assert answers[4].startswith("200 {'fault': [1, 'Exception: method \"no_such_call\" is not"), answers
    assert answers[5].startswith("200 {'fault': [1, 'TypeError: "), answers
    assert answers[6] == '400'  # a negative Content-Length, which would have the daemon wait
    assert answers[7] == f'xml-rpc {cli.domain_id}'
    assert lines(ros2(cli, 'daemon', 'status')) == ['The daemon is running']  # still serving


# What `ros2 daemon stop` does, with the domain's participants counted before and the moment it returns.
STOP_AND_COUNT = '''
from ros2cli.daemon.client import shutdown_daemon
from ros2cli.node.settle import local_participants
before = local_participants()
shutdown_daemon()
print(before, local_participants())
'''


def test_a_stopped_daemon_has_left_the_graph_when_stop_returns(cli):
    # Else a daemon started next sees this one's participant, counts it, and misses a node of the
    # graph when it leaves (the first answer of a just started daemon was partial).
    for _ in range(3):
        assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon has been started']
        counted = subprocess.run([sys.executable, '-c', STOP_AND_COUNT], env=cli.env, capture_output=True,
                                 text=True, timeout=30, check=True)
        before, after = map(int, counted.stdout.split())
        assert after == before - 1, counted.stdout


# s: how long a daemon that a verb started stays alone (ROS2CLI_DAEMON_ALONE_TIMEOUT) in the test below
ALONE_TIMEOUT = 3.0
# s: the most its leaving can lag behind (the daemon looks at its company after each request, or
# after 1 s without one), plus a margin
ALONE_CHECK_LAG = 2.0


@pytest.fixture
def empty_domain():
    """A second ROS domain of the test's own, with nothing running in it (its daemon is stopped after)."""
    with RosHarness() as harness:
        yield harness


def test_first_call_starts_a_daemon_that_leaves_when_alone(cli, empty_domain):
    # `ros2 daemon start` means: stay, even alone. That daemon, alone in its domain from the start, is
    # looked at once the one that a verb started has left (with the same timeout).
    for domain in (cli, empty_domain):
        domain.env['ROS2CLI_DAEMON_ALONE_TIMEOUT'] = str(ALONE_TIMEOUT)
    assert lines(ros2(empty_domain, 'daemon', 'start')) == ['The daemon has been started']
    explicit_started = time.monotonic()
    talker = cli.run(FIXTURES, 'talker')
    assert ros2(cli, 'node', 'list').returncode == 0
    assert eventually(lambda: lines(ros2(cli, 'daemon', 'status')) == ['The daemon is running'], 10), \
        'no daemon answered within 10 s of the first `ros2 node list`'
    assert eventually(lambda: lines(ros2(cli, 'node', 'list')) == ['/talker']), \
        f"the node list is {lines(ros2(cli, 'node', 'list'))}, not the talker"
    talker_code = talker.stop()
    assert eventually(lambda: lines(ros2(cli, 'daemon', 'status')) == ['The daemon is not running'], 20), (
        f'the daemon still runs 20 s after the talker stopped (its exit code {talker_code}); '
        f"the node list is {lines(ros2(cli, 'node', 'list'))}, "
        f"{lines(ros2(cli, 'node', 'list', '--no-daemon'))} without the daemon; the daemon's view of "
        f"the talker: {lines(ros2(cli, 'node', 'info', '/talker'))}")
    assert lines(ros2(cli, 'daemon', 'start')) == ['The daemon has been started']
    # A negative check: past the time a daemon that a verb started would have left (passed by now, usually).
    time.sleep(max(0.0, explicit_started + ALONE_TIMEOUT + ALONE_CHECK_LAG - time.monotonic()))
    assert lines(ros2(empty_domain, 'daemon', 'status')) == ['The daemon is running']


# ---- ros2 service -----------------------------------------------------------------------------

PARAMETER_SERVICES = ['describe_parameters', 'get_parameter_types', 'get_parameters', 'get_type_description',
                      'list_parameters', 'set_parameters', 'set_parameters_atomically']


def test_service_list_type_find(graph):
    listing = lines(ros2(graph, 'service', 'list'))
    assert listing[:8] == ['/echo'] + [f'/echo_server/{name}' for name in PARAMETER_SERVICES]
    assert len(listing) == 1 + 7 * len(FIXTURE_NODES)
    assert lines(ros2(graph, 'service', 'list', '-c')) == [str(len(listing))]
    typed = lines(ros2(graph, 'service', 'list', '-t'))
    assert typed[:2] == ['/echo [std_srvs/srv/SetBool]',
                         '/echo_server/describe_parameters [rcl_interfaces/srv/DescribeParameters]']
    assert not any('_action' in name for name in listing)
    hidden = lines(ros2(graph, 'service', 'list', '--include-hidden-services'))
    assert '/fibonacci/_action/send_goal' in hidden
    assert lines(ros2(graph, 'service', 'type', '/echo')) == ['std_srvs/srv/SetBool']
    unknown = ros2(graph, 'service', 'type', '/nope')
    assert unknown.returncode == 1
    assert unknown.stdout == ''
    assert lines(ros2(graph, 'service', 'find', 'std_srvs/srv/SetBool')) == ['/echo']
    assert lines(ros2(graph, 'service', 'find', '-c', 'rcl_interfaces/srv/GetParameters')) == \
        [str(len(FIXTURE_NODES))]
    nothing = ros2(graph, 'service', 'find', 'std_srvs/SetBool')
    assert nothing.returncode == 0
    assert nothing.stdout == ''


def test_service_call_exact_output(graph):
    result = ros2(graph, 'service', 'call', '/echo', 'std_srvs/srv/SetBool', '{data: true}')
    assert result.returncode == 0, result.stderr
    output = [line for line in lines(result) if line != 'waiting for service to become available...']
    assert output == ['requester: making request: std_srvs.srv.SetBool_Request(data=True)', '', 'response:',
                      "std_srvs.srv.SetBool_Response(success=True, message='received True')", '']
    defaults = ros2(graph, 'service', 'call', 'echo', 'std_srvs/SetBool')
    assert "std_srvs.srv.SetBool_Response(success=False, message='received False')" in defaults.stdout


def test_service_call_repeats_at_a_rate(graph):
    call = graph.command(['ros2', 'service', 'call', '-r', '5', '/echo', 'std_srvs/srv/SetBool',
                          'data: true'])
    call.wait_for('^response:$', count=3, timeout=20)
    assert call.stop() == 2
    assert 'Traceback' not in call.output


@pytest.mark.parametrize(('args', 'fragments'), [
    (['std_srvs/srv/SetBol'], ['The passed service type is invalid', "did you mean 'SetBool'?"]),
    (['std_srvs/msg/SetBool'], ['The passed service type is invalid',
                                "'std_srvs/msg/SetBool' is not a service"]),
    (['std_srvs/srv/SetBool', '{dat: true}'], ['Failed to populate field', "unknown field 'dat'",
                                                "did you mean 'data'?"]),
    (['std_srvs/srv/SetBool', '{data: 3}'], ["field 'data' expects a boolean"]),
    (['std_srvs/srv/SetBool', 'data: [true'], ['Failed to populate field: invalid YAML']),
    (['std_srvs/srv/SetBool', '-r', '0'], ['rate must be greater than zero']),
])
def test_service_call_bad_input(graph, args, fragments):
    assert_one_line_error(ros2(graph, 'service', 'call', '/echo', *args), *fragments)


def test_service_call_unknown_service_says_so_while_waiting(graph):
    call = graph.command(['ros2', 'service', 'call', '/ech', 'std_srvs/srv/SetBool'])
    call.wait_for("No server for service '/ech' yet \\(did you mean '/echo'\\?\\); still waiting", timeout=20)
    assert call.stop() == 2
    assert 'Traceback' not in call.output


# ---- ros2 param -------------------------------------------------------------------------------

PARAMETER_NAMES = ['bool_array_param', 'bool_param', 'double_array_param', 'double_param', 'fixed',
                   'foo.bar.str_param', 'foo.str_param', 'int_array_param', 'int_param', 'level',
                   'start_type_description_service', 'str_array_param', 'str_param', 'use_sim_time']
PARAMETER_DUMP = """/parameter_node:
  ros__parameters:
    bool_array_param:
    - false
    - false
    - true
    bool_param: true
    double_array_param:
    - 3.125
    - 6.25
    - 12.5
    double_param: 1.23
    fixed: cannot change
    foo:
      bar:
        str_param: foobar
      str_param: foo
    int_array_param:
    - 1
    - 2
    - 3
    int_param: 42
    level: 5
    start_type_description_service: true
    str_array_param:
    - foo
    - bar
    - baz
    str_param: Hello World
    use_sim_time: false

"""


def test_param_list(graph):
    assert lines(ros2(graph, 'param', 'list', '/parameter_node')) == [f'  {n}' for n in PARAMETER_NAMES]
    assert lines(ros2(graph, 'param', 'list', 'parameter_node', '--filter', 'bool.*')) == \
        ['  bool_array_param', '  bool_param']
    assert lines(ros2(graph, 'param', 'list', '/parameter_node', '--param-type', '--filter', 'int')) == \
        ['  int_array_param (type: integer array)', '  int_param (type: integer)']
    everything = lines(ros2(graph, 'param', 'list'))
    assert [line for line in everything if not line.startswith('  ')] == [f'{n}:' for n in FIXTURE_NODES]
    assert everything[everything.index('/talker:') + 1:] == ['  rate', '  start_type_description_service',
                                                               '  use_sim_time']


@pytest.mark.parametrize(('name', 'expected'), [
    ('bool_param', 'Boolean value is: True'),
    ('int_param', 'Integer value is: 42'),
    ('double_param', 'Double value is: 1.23'),
    ('str_param', 'String value is: Hello World'),
    ('bool_array_param', 'Boolean values are: [False, False, True]'),
    ('int_array_param', 'Integer values are: [1, 2, 3]'),
    ('double_array_param', 'Double values are: [3.125, 6.25, 12.5]'),
    ('str_array_param', "String values are: ['foo', 'bar', 'baz']"),
    ('foo.bar.str_param', 'String value is: foobar'),
])
def test_param_get_every_type(graph, name, expected):
    assert lines(ros2(graph, 'param', 'get', '/parameter_node', name)) == [expected]


def test_param_get_hide_type_and_bad_names(graph):
    assert lines(ros2(graph, 'param', 'get', '/parameter_node', 'int_param', '--hide-type')) == ['42']
    assert_one_line_error(ros2(graph, 'param', 'get', '/parameter_node', 'int_parm'), 'Parameter not set',
                          "'int_parm'", "did you mean 'int_param'?")
    assert_one_line_error(ros2(graph, 'param', 'get', '/parameter_nod', 'int_param'), 'Node not found',
                          "did you mean '/parameter_node'?")
    assert_one_line_error(ros2(graph, 'param', 'list', 'invalid_ns/parameter_node'), 'Node not found')
    usage = ros2(graph, 'param', 'load')
    assert usage.returncode == 2
    assert 'ros2 param load: error: the following arguments are required: node_name, parameter_file' \
        in usage.stderr


def test_param_set_delete_and_their_errors(graph):
    node = '/mutable_params'
    assert lines(ros2(graph, 'param', 'set', node, 'int_param', '7')) == ['Set parameter successful']
    assert lines(ros2(graph, 'param', 'get', node, 'int_param')) == ['Integer value is: 7']
    assert lines(ros2(graph, 'param', 'set', node, 'int_array_param', '[4, 5]')) == \
        ['Set parameter successful']
    assert lines(ros2(graph, 'param', 'get', node, 'int_array_param')) == ['Integer values are: [4, 5]']
    wrong = ros2(graph, 'param', 'set', node, 'int_param', 'seven')
    assert_one_line_error(wrong, "Setting parameter failed: Wrong parameter type for 'int_param': "
                                 'expected integer, got string', code=0)
    assert_one_line_error(ros2(graph, 'param', 'set', node, 'fixed', 'x'),
                          'Setting parameter failed: Trying to set a read-only parameter: fixed.', code=0)
    assert_one_line_error(ros2(graph, 'param', 'set', node, 'level', '11'),
                          'Setting parameter failed', 'out of range', code=0)
    assert_one_line_error(ros2(graph, 'param', 'set', node, 'int_parm', '1'),
                          "Setting parameter failed: node '/mutable_params' has no parameter 'int_parm'",
                          "did you mean 'int_param'?", code=0)
    assert_one_line_error(ros2(graph, 'param', 'delete', node, 'int_param'),
                          'Deleting parameter failed: Static parameter cannot be undeclared', code=0)
    assert lines(ros2(graph, 'param', 'get', node, 'int_param')) == ['Integer value is: 7']


def test_param_describe(graph):
    result = ros2(graph, 'param', 'describe', '/parameter_node', 'level', 'fixed', 'levl')
    assert lines(result) == [
        'Parameter name: level', '  Type: integer', '  Description: A level from 0 to 10', '  Constraints:',
        '    Min value: 0', '    Max value: 10', '    Step: 1',
        'Parameter name: fixed', '  Type: string', '  Description: A read-only parameter', '  Constraints:',
        '    Read only: true']
    assert_one_line_error(result, "Parameter 'levl' is not declared by node '/parameter_node'",
                          "did you mean 'level'?", code=0)


def test_param_dump_exact_and_load_round_trip(graph, tmp_path):
    dump = ros2(graph, 'param', 'dump', '/parameter_node')
    assert dump.returncode == 0
    assert dump.stdout == PARAMETER_DUMP
    saved = tmp_path / 'params.yaml'
    changed = PARAMETER_DUMP.replace('/parameter_node:', '/mutable_params:').replace(
        'int_param: 42', 'int_param: -42').replace('str_param: Hello World', 'str_param: Bye World').replace(
        '    - 12.5', '    - 25.0')
    saved.write_text(changed)
    load = ros2(graph, 'param', 'load', '/mutable_params', str(saved))
    assert load.returncode == 0
    assert 'Set parameter int_param successful' in lines(load)
    assert 'Set parameter fixed failed: Trying to set a read-only parameter: fixed.' in load.stderr
    assert ros2(graph, 'param', 'dump', '/mutable_params').stdout == changed


def test_param_load_wildcard_and_overrides(graph, tmp_path):
    wildcard = tmp_path / 'wildcard.yaml'
    wildcard.write_text('/**:\n  ros__parameters:\n    str_param: Wildcard\n    int_param: 12345\n')
    refused = ros2(graph, 'param', 'load', '--no-use-wildcard', '/mutable_params', str(wildcard))
    assert_one_line_error(refused, 'Param file does not contain selected parameters')
    assert ros2(graph, 'param', 'load', '/mutable_params', str(wildcard)).returncode == 0
    assert lines(ros2(graph, 'param', 'get', '/mutable_params', 'int_param')) == ['Integer value is: 12345']
    overlay = tmp_path / 'overlay.yaml'
    overlay.write_text(wildcard.read_text()
                       + 'mutable_params:\n  ros__parameters:\n    str_param: Override\n')
    assert ros2(graph, 'param', 'load', '/mutable_params', str(overlay)).returncode == 0
    assert lines(ros2(graph, 'param', 'get', '/mutable_params', 'str_param')) == ['String value is: Override']


def test_param_load_bad_files(graph, tmp_path):
    missing = ros2(graph, 'param', 'load', '/mutable_params', str(tmp_path / 'none.yaml'))
    assert_one_line_error(missing, 'No such file or directory', 'none.yaml')
    broken = tmp_path / 'broken.yaml'
    broken.write_text('/mutable_params:\n  ros__parameters: [1\n')
    assert_one_line_error(ros2(graph, 'param', 'load', '/mutable_params', str(broken)),
                          'broken.yaml', 'invalid YAML (line 3')
    other = tmp_path / 'other.yaml'
    other.write_text('/mutable_param:\n  ros__parameters:\n    int_param: 1\n')
    assert_one_line_error(ros2(graph, 'param', 'load', '/mutable_params', str(other)),
                          'nothing for /mutable_params', "did you mean '/mutable_param'?")
    flat = tmp_path / 'flat.yaml'
    flat.write_text('/mutable_params:\n  int_param: 1\n')
    assert_one_line_error(ros2(graph, 'param', 'load', '/mutable_params', str(flat)),
                          'YAML file is not a valid ROS parameter file for node /mutable_params')
    # rclpy's parameter_dict_from_yaml_file (as upstream) makes a string of a mixed list; the node
    # refuses it for its integer parameter, on one line.
    mixed = tmp_path / 'mixed.yaml'
    mixed.write_text('/mutable_params:\n  ros__parameters:\n    int_param: [1, a]\n')
    result = ros2(graph, 'param', 'load', '/mutable_params', str(mixed))
    assert result.returncode == 0
    assert 'Traceback' not in result.stderr
    assert result.stderr.startswith('Set parameter int_param failed: ')
    assert result.stderr.count('\n') == 1


# ---- ros2 action ------------------------------------------------------------------------------

ACTION_TYPE = f'{FIXTURES}/action/Fibonacci'


def test_action_list_info_type(graph):
    assert lines(ros2(graph, 'action', 'list')) == ['/fibonacci']
    assert lines(ros2(graph, 'action', 'list', '-t')) == [f'/fibonacci [{ACTION_TYPE}]']
    assert lines(ros2(graph, 'action', 'list', '-c')) == ['1']
    assert lines(ros2(graph, 'action', 'info', '/fibonacci')) == [
        'Action: /fibonacci', 'Action clients: 0', 'Action servers: 1', '    /fibonacci_server']
    assert lines(ros2(graph, 'action', 'info', '/fibonacci', '-t')) == [
        'Action: /fibonacci', 'Action clients: 0', 'Action servers: 1',
        f'    /fibonacci_server [{ACTION_TYPE}]']
    assert lines(ros2(graph, 'action', 'info', '/fibonacci', '-c')) == [
        'Action: /fibonacci', 'Action clients: 0', 'Action servers: 1']
    assert lines(ros2(graph, 'action', 'type', '/fibonacci')) == [ACTION_TYPE]
    assert ros2(graph, 'action', 'find', ACTION_TYPE).returncode == 2  # a Rolling verb, not Jazzy's
    unknown = ros2(graph, 'action', 'info', '/fibonaci')
    assert lines(unknown) == ['Action: /fibonaci', 'Action clients: 0', 'Action servers: 0']
    assert_one_line_error(unknown, "No action '/fibonaci' in the graph (did you mean '/fibonacci'?)", code=0)
    assert ros2(graph, 'action', 'type', '/fibonaci').returncode == 1


def test_action_send_goal_exact_output(graph):
    result = ros2(graph, 'action', 'send_goal', '/fibonacci', ACTION_TYPE, '{order: 3}')
    assert result.returncode == 0, result.stderr
    output = lines(result)
    assert output[:4] == ['Waiting for an action server to become available...', 'Sending goal:',
                          '     order: 3', '']
    assert re.fullmatch('Goal accepted with ID: [0-9a-f]{32}', output[4])
    assert output[5:] == ['', 'Result:', '    sequence:', '- 0', '- 1', '- 1', '- 2', '',
                          'Goal finished with status: SUCCEEDED']


def test_action_send_goal_feedback(graph):
    result = ros2(graph, 'action', 'send_goal', '-f', 'fibonacci', ACTION_TYPE, 'order: 2')
    assert result.returncode == 0, result.stderr
    assert 'Feedback:\n    sequence:\n- 0\n- 1\n- 1\n\n' in result.stdout
    assert result.stdout.endswith('Goal finished with status: SUCCEEDED\n')


@pytest.mark.parametrize(('args', 'fragments'), [
    ([f'{FIXTURES}/action/Fibonaci'], ['The passed action type is invalid', "did you mean 'Fibonacci'?"]),
    ([ACTION_TYPE, '{ordr: 3}'], ['Failed to populate message fields', "unknown field 'ordr'",
                                 "did you mean 'order'?"]),
    ([ACTION_TYPE, '{order: 2.5}'], ["field 'order' expects an integer (int32), got 2.5"]),
    ([ACTION_TYPE, '{order: 3'], ['Failed to populate message fields: invalid YAML']),
])
def test_action_send_goal_bad_input(graph, args, fragments):
    assert_one_line_error(ros2(graph, 'action', 'send_goal', '/fibonacci', *args), *fragments)


def test_action_send_goal_to_a_mistyped_action_says_so_while_waiting(graph):
    goal = graph.command(['ros2', 'action', 'send_goal', '/fibonaci', ACTION_TYPE, '{order: 1}'])
    goal.wait_for("No action server for '/fibonaci' yet \\(did you mean '/fibonacci'\\?\\); still waiting",
                  timeout=20)
    assert goal.stop() == 2
    assert 'Traceback' not in goal.output


# ---- shell completion -------------------------------------------------------------------------

@pytest.mark.parametrize(('line', 'expected'), [
    ('ros2 run ros2cli_test_fi', [FIXTURES]),
    (f'ros2 run {FIXTURES} ta', ['talker']),
    ('ros2 node info /talk', ['/talker']),
    ('ros2 topic echo /cha', ['/chatter']),
    ('ros2 service type /ec', ['/echo', '/echo_server/describe_parameters']),
    ('ros2 action info /fib', ['/fibonacci']),
    ('ros2 interface show std_srvs/srv/SetB', ['std_srvs/srv/SetBool']),
    ('ros2 topic pub /x geometry_msgs/msg/Twis',
     ['geometry_msgs/msg/Twist', 'geometry_msgs/msg/TwistStamped']),
])
def test_shell_completion(graph, tmp_path, line, expected):
    output = tmp_path / 'completions'
    env = dict(graph.env, _ARGCOMPLETE='1', _ARGCOMPLETE_IFS='\n', COMP_LINE=line, COMP_POINT=str(len(line)),
               _ARGCOMPLETE_STDOUT_FILENAME=str(output))
    subprocess.run(['ros2'], env=env, capture_output=True, timeout=30, check=False)
    candidates = [c.strip() for c in output.read_text().splitlines()]
    for name in expected:
        assert name in candidates, candidates
