"""The official ROS 2 Jazzy tutorials the course sends students to, followed step by step here.

Each test drives the commands a tutorial page gives, in a fresh ROS domain, and checks the output
the page shows. Where a tutorial has the student type code, the test writes code of the same shape
in its own words (the tutorials' files are not copied).
"""

from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import textwrap
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import yaml
from gates import prerequisite_missing
from netns import TestLan
from olive_sim.network_hosts import ip
from owl_common.processes import RosProcess
from ros_harness import RosHarness, wait_until
from student_workspace import shell

TIMEOUT = 60


def ros2(ros: RosHarness, *args: str, timeout: float = TIMEOUT) -> subprocess.CompletedProcess:
    result = subprocess.run(['ros2', *args], env=ros.env, capture_output=True, text=True, timeout=timeout,
                            check=False)
    assert 'Traceback' not in result.stderr, result.stderr
    return result


# ---- Writing a simple service and client (Python) ---------------------------------------------

SERVICE = '''
import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.node import Node


class AddingService(Node):

    def __init__(self):
        super().__init__('minimal_service')
        self.srv = self.create_service(AddTwoInts, 'add_two_ints', self.add)

    def add(self, request, response):
        response.sum = request.a + request.b
        self.get_logger().info('Incoming request\\na: %d b: %d' % (request.a, request.b))
        return response


def main():
    rclpy.init()
    node = AddingService()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.try_shutdown()
'''

CLIENT = '''
import sys

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.node import Node


class AddingClient(Node):

    def __init__(self):
        super().__init__('minimal_client_async')
        self.cli = self.create_client(AddTwoInts, 'add_two_ints')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again...')

    def send_request(self, a, b):
        return self.cli.call_async(AddTwoInts.Request(a=a, b=b))


def main():
    rclpy.init()
    client = AddingClient()
    a, b = int(sys.argv[1]), int(sys.argv[2])
    future = client.send_request(a, b)
    rclpy.spin_until_future_complete(client, future)
    client.get_logger().info('Result of add_two_ints: for %d + %d = %d' % (a, b, future.result().sum))
    client.destroy_node()
    rclpy.shutdown()
'''


def test_writing_a_simple_service_and_client_in_python(ros: RosHarness, tmp_path: Path):
    workspace = tmp_path / 'ros2_ws'
    (workspace / 'src').mkdir(parents=True)
    created = shell(workspace / 'src', 'ros2 pkg create --build-type ament_python --license Apache-2.0 '
                    'py_srvcli --dependencies rclpy example_interfaces', env=ros.env)
    assert created.returncode == 0, created.stderr
    package = workspace / 'src' / 'py_srvcli'
    (package / 'py_srvcli' / 'service_member_function.py').write_text(SERVICE)
    (package / 'py_srvcli' / 'client_member_function.py').write_text(CLIENT)
    setup = package / 'setup.py'
    setup.write_text(setup.read_text().replace(
        "'console_scripts': [\n",
        "'console_scripts': [\n"
        "            'service = py_srvcli.service_member_function:main',\n"
        "            'client = py_srvcli.client_member_function:main',\n"))
    # The tutorial's dependency step: example_interfaces is there, so rosdep has nothing to install.
    rosdep = shell(workspace, 'rosdep install -i --from-path src --rosdistro jazzy -y', env=ros.env)
    assert rosdep.returncode == 0, rosdep.stdout + rosdep.stderr
    assert '#All required rosdeps installed successfully' in rosdep.stdout
    build = shell(workspace, 'colcon build --packages-select py_srvcli', env=ros.env)
    assert build.returncode == 0, build.stdout + build.stderr
    setup_file = workspace / 'install' / 'setup.bash'
    service = ros.command(['bash', '-c', f'source {setup_file} && exec ros2 run py_srvcli service'],
                          label='service')
    client = shell(workspace, 'ros2 run py_srvcli client 2 3', env=ros.env, timeout=TIMEOUT)
    assert client.returncode == 0, client.stdout + client.stderr
    result = r'\[INFO\] \[\d+\.\d+\] \[minimal_client_async\]: Result of add_two_ints: for 2 \+ 3 = 5'
    assert re.search(result, client.stderr), client.stderr
    service.wait_for(r'\[minimal_service\]: Incoming request$')
    service.wait_for(r'^a: 2 b: 3$')


# ---- Understanding services; Configure service introspection ----------------------------------

# One event as `ros2 service echo --flow-style` prints it.
EVENT = (r'^info:\n  event_type: (\w+)\n  stamp:\n    sec: \d+\n    nanosec: \d+\n'
         r'  client_gid: \[(?:\d+, ){15}\d+\]\n  sequence_number: (\d+)\n'
         r'request: (.*)\nresponse: (.*)\n---$')


def wait_for_events(process: RosProcess, pattern: str, count: int) -> list[re.Match]:
    """The first count matches of a multi-line pattern in the process's output, once there are that many."""
    regex = re.compile(pattern, re.M)
    try:
        wait_until(lambda: len(regex.findall(process.output)) >= count, 20, f'{count} events')
    except AssertionError as error:
        raise AssertionError(f'{process.label}: {error}; output:\n{process.tail()}') from None
    return list(regex.finditer(process.output))[:count]


def test_service_info_and_echo_of_the_introspection_demo(ros: RosHarness):
    ros.command(['ros2', 'launch', 'demo_nodes_cpp', 'introspect_services_launch.py'], label='demo')
    wait_until(lambda: ros2(ros, 'service', 'info', '/add_two_ints').stdout.endswith('Services count: 1\n')
               and 'Clients count: 1' in ros2(ros, 'service', 'info', '/add_two_ints').stdout,
               30, 'the introspection demo on the graph')
    assert ros2(ros, 'service', 'info', '/add_two_ints').stdout.splitlines() == [
        'Type: example_interfaces/srv/AddTwoInts', 'Clients count: 1', 'Services count: 1']
    # Introspection is off: echo says so and waits.
    echo_off = ros.command(['ros2', 'service', 'echo', '/add_two_ints'], label='echo off')
    echo_off.wait_for(r"No publishers on topic '/add_two_ints/_service_event'; is service introspection on "
                      r'the client or server enabled\?', timeout=20)
    assert echo_off.stop() == 2  # Ctrl-C: the verbs exit with SIGINT's number, as upstream's
    for node, parameter in (('/introspection_service', 'service_configure_introspection'),
                            ('/introspection_client', 'client_configure_introspection')):
        result = ros2(ros, 'param', 'set', node, parameter, 'contents')
        assert result.stdout == 'Set parameter successful\n', result.stdout + result.stderr
    echo = ros.command(['ros2', 'service', 'echo', '--flow-style', '/add_two_ints'], label='echo')
    events = wait_for_events(echo, EVENT, 8)
    shown = {(m.group(1), m.group(3), m.group(4)) for m in events}
    assert shown >= {('REQUEST_SENT', '[{a: 2, b: 3}]', '[]'), ('REQUEST_RECEIVED', '[{a: 2, b: 3}]', '[]'),
                     ('RESPONSE_SENT', '[]', '[{sum: 5}]'), ('RESPONSE_RECEIVED', '[]', '[{sum: 5}]')}, shown
    assert echo.stop() == 2
    # Metadata only on the client: its events come without the request and response.
    assert ros2(ros, 'param', 'set', '/introspection_client', 'client_configure_introspection',
                'metadata').returncode == 0
    csv = ros.command(['ros2', 'service', 'echo', '--csv', '/add_two_ints'], label='echo csv')
    rows = wait_for_events(csv, r'^(\d),\d+,\d+,(?:\d+,){16}\d+(,.*)?$', 8)
    # REQUEST_SENT (0) now comes from the client without the request: nothing after the sequence number.
    assert any(m.group(1) == '0' and not m.group(2) for m in rows), [m.group(0) for m in rows]
    assert csv.stop() == 2


@pytest.mark.parametrize(('value', 'reason'), [
    ('Contents', "must be one of 'disabled', 'metadata', or 'contents'"),
    ('1', "Wrong parameter type for 'service_configure_introspection': expected string, got integer"),
])
def test_an_introspection_value_that_names_no_state_is_refused(ros: RosHarness, value: str, reason: str):
    ros.run('demo_nodes_cpp', 'introspection_service')
    ros.probe.wait_for_node('introspection_service', timeout=20)
    result = ros2(ros, 'param', 'set', '/introspection_service', 'service_configure_introspection', value)
    assert f'Setting parameter failed: {reason}' in result.stdout + result.stderr, result
    get = ros2(ros, 'param', 'get', '/introspection_service', 'service_configure_introspection')
    assert get.stdout == 'String value is: disabled\n', get.stdout + get.stderr


@pytest.mark.parametrize(('args', 'message'), [
    (['info', '/no_such_service'], "Unknown service '/no_such_service'"),
    (['echo', '/no_such_service'], "Cannot find type for '/no_such_service'"),
    (['echo', '/add_two_ints', 'example_interfaces/srv/NoSuch'],
     "The service type 'example_interfaces/srv/NoSuch' is invalid"),
    (['echo', '/add_two_ints', 'not a type'], "The service type 'not a type' is invalid"),
    (['echo', '/add_two_ints', '--truncate-length', '-3'], 'argument --truncate-length/-l'),
])
def test_service_info_and_echo_bad_input_one_line(ros: RosHarness, args: list[str], message: str):
    result = ros2(ros, 'service', *args)
    assert result.returncode == (2 if args[-1] == '-3' else 1), result
    # The error is the last line (argparse's usage lines come before it).
    assert message in result.stderr.strip().splitlines()[-1], result.stderr
    assert result.stdout == ''


# ---- Using talker and listener; Integrating launch files into packages -------------------------

def test_cpp_talker_and_py_listener(ros: RosHarness):
    talker = ros.command(['ros2', 'run', 'demo_nodes_cpp', 'talker'], label='talker')
    listener = ros.command(['ros2', 'run', 'demo_nodes_py', 'listener'], label='listener')
    talker.wait_for(r"\[INFO\] \[\d+\.\d+\] \[talker\]: Publishing: 'Hello World: 1'", timeout=20)
    heard = listener.wait_for(r'\[listener\]: I heard: \[Hello World: (\d+)\]', timeout=20)
    assert int(heard[0].group(1)) >= 1
    for process in (talker, listener):
        process.stop_cleanly()
        assert 'Traceback' not in process.output


def test_py_talker_counts_from_zero_and_servers_answer_the_demo_clients(ros: RosHarness):
    talker = ros.command(['ros2', 'run', 'demo_nodes_py', 'talker'], label='talker')
    talker.wait_for(r'\[talker\]: Publishing: "Hello World: 0"', timeout=20)
    # Before there is a server, Python's clients print their waiting line and C++'s log it.
    waiting = {package: ros.command(['ros2', 'run', package, 'add_two_ints_client'], label=package)
               for package in ('demo_nodes_py', 'demo_nodes_cpp')}
    line = r'service not available, waiting again\.\.\.$'
    waiting['demo_nodes_py'].wait_for('^' + line, timeout=20)
    waiting['demo_nodes_cpp'].wait_for(r'^\[INFO\] \[\d+\.\d+\] \[add_two_ints_client\]: ' + line, timeout=20)
    ros.command(['ros2', 'run', 'demo_nodes_cpp', 'add_two_ints_server'], label='server')
    for client in waiting.values():
        client.wait_for(r'\[add_two_ints_client\]: Result of add_two_ints: 5$', timeout=20)
        assert client.wait(10) == 0, client.tail()
    with ThreadPoolExecutor(max_workers=2) as pool:  # the two clients side by side
        results = list(pool.map(lambda client: ros2(ros, 'run', *client),
                                (('demo_nodes_py', 'add_two_ints_client'),
                                 ('demo_nodes_cpp', 'add_two_ints_client_async'))))
    for result in results:
        assert result.returncode == 0, result.stderr
        assert re.search(r'\[add_two_ints_client\]: Result of add_two_ints: 5$', result.stderr, re.M), \
            result.stderr


def test_the_cpp_server_with_one_shot_ends_after_its_first_answer(ros: RosHarness):
    server = ros.command(['ros2', 'run', 'demo_nodes_cpp', 'add_two_ints_server', '--ros-args', '-p',
                          'one_shot:=true'], label='one-shot server')
    client = ros2(ros, 'run', 'demo_nodes_cpp', 'add_two_ints_client')
    assert 'Result of add_two_ints: 5' in client.stderr, client.stderr
    assert server.wait(10) == 0, server.tail()
    assert 'Traceback' not in server.output
    # demo_nodes_py's server has no such parameter, as upstream's: it keeps serving.
    py_server = ros.command(['ros2', 'run', 'demo_nodes_py', 'add_two_ints_server', '--ros-args', '-p',
                             'one_shot:=true'], label='py server')
    assert 'Result of add_two_ints: 5' in ros2(ros, 'run', 'demo_nodes_py', 'add_two_ints_client').stderr
    time.sleep(1.0)
    assert py_server.running(), py_server.tail()


def test_the_python_introspection_demo_is_one_executable_with_both_nodes(ros: RosHarness):
    # The service introspection page's Python command line.
    demo = ros.command(['ros2', 'run', 'demo_nodes_py', 'introspection', '--ros-args', '-p',
                        'client_configure_introspection:=metadata', '-p',
                        'service_configure_introspection:=metadata'], label='introspection')
    demo.wait_for(r'\[introspection_client\]: Result of add_two_ints: 5', timeout=30)
    demo.wait_for(r'\[introspection_service\]: Incoming request', timeout=5)
    for node, parameter in (('/introspection_service', 'service_configure_introspection'),
                            ('/introspection_client', 'client_configure_introspection')):
        assert ros2(ros, 'param', 'get', node, parameter).stdout == 'String value is: metadata\n'
    demo.stop_cleanly()
    assert 'Traceback' not in demo.output


LAUNCH_FILES = {
    'my_script_launch.py': '''
        from launch import LaunchDescription
        from launch_ros.actions import Node


        def generate_launch_description():
            return LaunchDescription([
                Node(package='demo_nodes_cpp', executable='talker', name='talker'),
            ])
        ''',
    'my_script_launch.xml': '''
        <launch>
          <node pkg="demo_nodes_cpp" exec="talker" name="talker"/>
        </launch>
        ''',
    'my_script_launch.yaml': '''
        launch:
        - node:
            pkg: "demo_nodes_cpp"
            exec: "talker"
            name: "talker"
        ''',
}


@pytest.mark.parametrize('launch_file', sorted(LAUNCH_FILES))
def test_integrating_launch_files_into_packages(ros: RosHarness, tmp_path: Path, launch_file: str):
    workspace = tmp_path / 'launch_ws'
    (workspace / 'src').mkdir(parents=True)
    created = shell(workspace / 'src', 'ros2 pkg create --build-type ament_python --license Apache-2.0 '
                    'py_launch_example', env=ros.env)
    assert created.returncode == 0, created.stderr
    package = workspace / 'src' / 'py_launch_example'
    (package / 'launch').mkdir()
    (package / 'launch' / launch_file).write_text(textwrap.dedent(LAUNCH_FILES[launch_file]))
    setup = package / 'setup.py'
    text = setup.read_text()
    text = 'import os\nfrom glob import glob\n' + text.replace(
        "('share/' + package_name, ['package.xml']),",
        "('share/' + package_name, ['package.xml']),\n"
        "        (os.path.join('share', package_name, 'launch'), glob('launch/*')),")
    setup.write_text(text)
    build = shell(workspace, 'colcon build', env=ros.env)
    assert build.returncode == 0, build.stdout + build.stderr
    setup_file = workspace / 'install' / 'setup.bash'
    command = f'source {setup_file} && exec ros2 launch py_launch_example {launch_file}'
    launch = ros.command(['bash', '-c', command], label='launch')
    launch.wait_for(r"\[talker-1\] \[INFO\] \[\d+\.\d+\] \[talker\]: Publishing: 'Hello World: 1'",
                    timeout=30)
    launch.stop_cleanly()


# ---- Launching nodes ---------------------------------------------------------------------------

def test_multisim_names_its_simulators_as_upstream(ros: RosHarness):
    ros.command(['ros2', 'launch', 'turtlesim', 'multisim.launch.py'], label='multisim')
    wait_until(lambda: ros2(ros, 'node', 'list').stdout == '/turtlesim1/turtlesim\n/turtlesim2/turtlesim\n',
               30, 'both simulators in ros2 node list')
    moved = ros2(ros, 'topic', 'pub', '-1', '/turtlesim1/turtle1/cmd_vel', 'geometry_msgs/msg/Twist',
                 '{linear: {x: 2.0}}')
    assert moved.returncode == 0, moved.stderr


# ---- Using ros2doctor to identify issues -------------------------------------------------------

def doctor(ros: RosHarness, *args: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    result = subprocess.run(['ros2', 'doctor', *args], env={**ros.env, **(env or {})}, capture_output=True,
                            text=True, timeout=TIMEOUT, check=False)
    assert 'Traceback' not in result.stderr, result.stderr
    assert result.returncode == 0, result.stdout + result.stderr  # upstream's: findings are in the output
    return result


def test_doctor_checks_a_clean_setup_then_finds_what_the_tutorial_shows(ros: RosHarness):
    clean = doctor(ros)
    assert clean.stdout == '\nAll 5 checks passed\n\n', clean.stdout + clean.stderr
    # The tutorial's turtlesim: its pose and color topics are published with nobody listening.
    ros.run('turtlesim', 'turtlesim_node')
    ros.probe.wait_for_node('turtlesim', timeout=20)
    ignored = doctor(ros)
    assert ignored.stdout == '\nAll 5 checks passed\n\n'  # warnings do not fail a check by default
    assert 'UserWarning: Publisher without subscriber detected on /turtle1/pose.' in ignored.stderr
    assert 'UserWarning: Subscriber without publisher detected on /turtle1/cmd_vel.' in ignored.stderr
    failed = doctor(ros, '--include-warnings', '--report-failed')
    assert failed.stdout.startswith('\n1/5 check(s) failed\n\nFailed modules: topic\n\n   TOPIC LIST\n'), \
        failed.stdout
    assert re.search(r'^topic {15}: /turtle1/pose\npublisher count {5}: 1\nsubscriber count {4}: 0$',
                     failed.stdout, re.M), failed.stdout


def test_doctor_finds_a_qos_mismatch(ros: RosHarness):
    ros.command(['ros2', 'topic', 'pub', '--qos-reliability', 'best_effort', '/chatter',
                 'std_msgs/msg/String', '{data: hi}'], label='best effort publisher')
    ros.command(['ros2', 'topic', 'echo', '--qos-reliability', 'reliable', '/chatter', 'std_msgs/msg/String'],
                label='reliable subscriber')
    wait_until(lambda: 'QoS compatibility error' in doctor(ros).stderr, 30, 'the mismatch found')
    result = doctor(ros)
    assert ("UserWarning: ERROR: QoS compatibility error found on topic '/chatter': "
            'Best effort publisher and reliable subscription;') in result.stderr, result.stderr
    assert result.stdout == '\n1/5 check(s) failed\n\nFailed modules: middleware\n'
    report = doctor(ros, '--report').stdout
    status = 'compatibility status    : ERROR: Best effort publisher and reliable subscription;'
    assert status in report, report
    for header in ('NETWORK CONFIGURATION', 'PACKAGE VERSIONS', 'PLATFORM INFORMATION',
                   'QOS COMPATIBILITY LIST', 'RMW MIDDLEWARE', 'ROS 2 INFORMATION', 'TOPIC LIST'):
        assert f'\n   {header}\n' in report
    assert re.search(r'^middleware name    : rmw_\w+$', report, re.M), report
    assert re.search(r'^rclpy +: pinned=([\d.]+), local=\1$', report, re.M), report


@pytest.mark.parametrize(('env', 'finding'), [
    ({'ROS_DISTRO': ''}, 'UserWarning: ERROR: ROS_DISTRO is not set.'),
    ({'ROS_DISTRO': 'iron'}, 'UserWarning: Distribution iron is no longer supported or deprecated.'),
    ({'ROS_AUTOMATIC_DISCOVERY_RANGE': 'EVERYWHERE'},
     "UserWarning: ERROR: ROS_AUTOMATIC_DISCOVERY_RANGE is 'EVERYWHERE'; it must be one of"),
    ({'ROS_DOMAIN_ID': '300'},
     "UserWarning: ERROR: ROS_DOMAIN_ID is '300'; it must be a number from 0 to 232."),
])
def test_doctor_says_what_is_wrong_with_the_setup(ros: RosHarness, env: dict[str, str], finding: str):
    result = doctor(ros, '-iw', '--exclude-packages', env=env)
    assert finding in result.stderr, result.stderr
    summary = r'\n1/4 check\(s\) failed\n\nFailed modules: (network|platform)\n$'
    assert re.match(summary, result.stdout), result.stdout


@pytest.mark.parametrize('args', [['--report', '--report-failed'], ['--no-such-option']])
def test_doctor_bad_options_are_one_usage_error(args: list[str]):
    result = subprocess.run(['ros2', 'doctor', *args], capture_output=True, text=True, timeout=TIMEOUT,
                            check=False)
    assert result.returncode == 2
    assert 'Traceback' not in result.stderr
    assert re.match(r'ros2( doctor)?: error: ', result.stderr.splitlines()[-1]), result.stderr


def unshare_uts_works() -> bool:
    """Whether this process may give a child its own hostname (a UTS namespace; root)."""
    try:
        return subprocess.run(['unshare', '--uts', 'hostname', 'uts-check'], capture_output=True,
                              timeout=TIMEOUT, check=False).returncode == 0
    except FileNotFoundError:
        return False


def hello_tables(process: RosProcess) -> list[dict[str, list[str]]]:
    """The hostnames under 'Subscribed from:' and 'Received from:' of each complete table printed so far."""
    tables: list[dict[str, list[str]]] = []
    table: dict[str, list[str]] = {}
    section = None
    for line in process.output.splitlines():
        if line == 'MULTIMACHINE COMMUNICATION SUMMARY':
            table, section = {'Subscribed from:': [], 'Received from:': []}, None
        elif line in table:
            section = line
        elif line == '-' * 60:
            tables.append(table)
            section = None
        elif not line.startswith(' ' * 16):  # a count line ends the section of hosts
            section = None
        elif section and line.split()[0] != 'Hostname':
            table[section].append(line.split()[0])
    return tables


def test_doctor_hello_on_two_hosts_hear_each_other(ros: RosHarness):
    """Two laptops on one LAN, each a network namespace with a hostname of its own.

    Namespaces, because hello's multicast port (49150) is fixed and inside Linux's ephemeral range: on
    this machine any other test's DDS participant may hold it by chance, and hello then says it cannot
    receive (as it should for a user). A suite run once saw exactly that.
    """
    if not unshare_uts_works():
        prerequisite_missing('`unshare --uts` cannot give a process another hostname here (it needs root)')
    lan = TestLan()
    try:
        hellos = {}
        for host, address in (('laptop-a', '10.42.0.101'), ('laptop-b', '10.42.0.102')):
            namespace = lan.add_host(host, address)
            # A LAN host reaches multicast groups through its default route; these hosts have none.
            ip('-n', namespace, 'route', 'add', '224.0.0.0/4', 'dev', 'eth0')
            hellos[host] = lan.run(
                host, f"unshare --uts sh -c 'hostname {host} && exec ros2 doctor hello -pp 0.5'",
                {'OWL_NETWORK': 'open', 'ROS_DOMAIN_ID': str(ros.domain_id)}, label=f'hello on {host}')

        def heard(listener: str, speaker: str) -> bool:  # over ROS and over multicast, in one table
            return any(speaker in table['Subscribed from:'] and speaker in table['Received from:']
                       for table in hello_tables(hellos[listener]))

        wait_until(lambda: heard('laptop-a', 'laptop-b') and heard('laptop-b', 'laptop-a'), 40,
                   'each hello hearing the other')
        local = hellos['laptop-a']
        assert all('laptop-a' not in [*table['Subscribed from:'], *table['Received from:']]
                   for table in hello_tables(local))  # its own hellos are not counted
        assert 'Multicast Group/Port: 225.0.0.1/49150, Sent Msg Count: ' in local.output
        assert '                Hostname             Msg Count /0.5s' in local.output
        for process in hellos.values():
            assert process.stop() == 0, process.tail()  # Ctrl-C is how hello ends, as upstream's
            assert 'Traceback' not in process.output, process.output
    finally:
        lan.close()


# ---- Recording and playing back data -----------------------------------------------------------

def moving(pose) -> bool:
    return bool(pose.linear_velocity or pose.angular_velocity)


def rest_after_driving(poses: list, since: int, what: str):
    """The first pose at rest after the turtle last moved in poses[since:] (a list Probe.collect fills).

    The turtle stops 1 s after its last velocity command; it must have moved since poses[since].
    """
    def resting():
        later = poses[since:]
        last_moving = max((i for i, pose in enumerate(later) if moving(pose)), default=None)
        if last_moving is None:
            return None
        return next((pose for pose in later[last_moving + 1:] if not moving(pose)), None)

    wait_until(resting, 10, what)
    return resting()


def test_record_info_and_play_move_the_turtle_along_the_same_path(ros: RosHarness, tmp_path: Path):
    from std_srvs.srv import Empty
    from turtlesim.msg import Pose

    ros.run('turtlesim', 'turtlesim_node')
    ros.probe.wait_for_node('turtlesim', timeout=20)
    poses = ros.probe.collect(Pose, '/turtle1/pose')
    wait_until(lambda: poses, 10, 'a pose')
    start = poses[-1]
    record = ros.command(['ros2', 'bag', 'record', '-o', 'subset', '/turtle1/cmd_vel', '/turtle1/pose'],
                         label='record', cwd=str(tmp_path))
    record.wait_for(r"\[rosbag2_recorder\]: Subscribed to topic '/turtle1/pose'", timeout=20)
    record.wait_for(r"\[rosbag2_recorder\]: Subscribed to topic '/turtle1/cmd_vel'", timeout=20)
    # What the tutorial does with the arrow keys: drive a curve for a while.
    # -w 2: once both turtlesim and the recorder hear it.
    driving = len(poses)
    driven = ros2(ros, 'topic', 'pub', '-w', '2', '-r', '20', '-t', '15', '/turtle1/cmd_vel',
                  'geometry_msgs/msg/Twist', '{linear: {x: 1.5}, angular: {z: 1.0}}')
    assert driven.returncode == 0, driven.stderr
    end = rest_after_driving(poses, driving, 'the turtle at rest after the drive')
    record.stop_cleanly()
    assert math.dist((start.x, start.y), (end.x, end.y)) > 1.0
    bag = tmp_path / 'subset'
    assert sorted(p.name for p in bag.iterdir()) == ['metadata.yaml', 'subset_0.mcap']

    info = ros2(ros, 'bag', 'info', str(bag))
    assert info.returncode == 0, info.stderr
    lines = info.stdout.splitlines()
    assert lines[1] == 'Files:             subset_0.mcap'
    assert lines[3] == 'Storage id:        mcap'
    counts = dict(re.findall(r'Topic: (\S+) \| Type: \S+ \| Count: (\d+) \| Serialization Format: cdr',
                             info.stdout))
    assert int(counts['/turtle1/cmd_vel']) == 15, info.stdout
    assert int(counts['/turtle1/pose']) > 100, info.stdout

    # Back to the start (the test's own step, not the tutorial's), then the bag's commands only: the
    # turtle drives the same curve.
    ros.probe.call(Empty, '/reset', Empty.Request())
    wait_until(lambda: math.dist((poses[-1].x, poses[-1].y), (start.x, start.y)) < 0.01, 10,
               'the turtle back at the start')
    playing = len(poses)
    played = ros2(ros, 'bag', 'play', '--topics', '/turtle1/cmd_vel', '--', str(bag))
    assert played.returncode == 0, played.stderr
    replayed = rest_after_driving(poses, playing, 'the turtle at rest after the replay')
    assert math.dist((replayed.x, replayed.y), (end.x, end.y)) < 0.5, (replayed, end)


def test_play_waits_for_a_subscriber_that_discovery_has_not_shown_yet(ros: RosHarness, tmp_path: Path):
    # On a busy machine a subscriber can take over a second to show up in a new node's graph. Play
    # waits until every participant of this machine is seen (ros2cli.node.settle), then for its
    # subscribers to match, so the listener hears the bag from its first message.
    from rclpy.serialization import serialize_message
    from ros2bag.bag import BagWriter
    from std_msgs.msg import String

    bag = tmp_path / 'chatter'
    writer = BagWriter(bag)
    writer.add_topic('/chatter', 'std_msgs/msg/String', 'string data', [], '')
    for count in range(5):
        writer.write('/chatter', serialize_message(String(data=f'Hello World: {count}')), (count + 1) * 10**8)
    writer.close()
    listener = ros.run('demo_nodes_py', 'listener')
    ros.probe.wait_for_node('listener', timeout=20)
    # Held up, the listener cannot answer the player's discovery until it goes on.
    os.kill(listener.pid, signal.SIGSTOP)
    held_at = time.monotonic()
    try:
        player = ros.command(['ros2', 'bag', 'play', str(bag)], label='play')
        player.wait_for(r'\[rosbag2_player\]: Playing', timeout=20)
        time.sleep(0.7)  # past the 0.3 s play once gave discovery
    finally:
        os.kill(listener.pid, signal.SIGCONT)
    went_on_at = time.monotonic()
    assert player.wait(timeout=20) == 0, player.output
    ended = time.monotonic() - went_on_at
    timing = f'listener held up {went_on_at - held_at:.2f} s; play ended {ended:.2f} s after'
    try:
        listener.wait_for(r'I heard: \[Hello World: 4\]', timeout=10)
    except AssertionError as error:
        raise AssertionError(f'{error}\n{timing}') from None
    heard = re.findall(r'I heard: \[Hello World: (\d)\]', listener.output)
    assert heard == ['0', '1', '2', '3', '4'], listener.output


def test_a_recorded_bag_reads_back_with_the_mcap_librarys_own_reader(ros: RosHarness, tmp_path: Path):
    from example_interfaces.srv import AddTwoInts
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    from rclpy.serialization import deserialize_message
    from ros2bag.interfaces import import_type
    from std_msgs.msg import String

    ros.command(['ros2', 'launch', 'demo_nodes_cpp', 'introspect_services_launch.py'], label='demo')
    ros.command(['ros2', 'run', 'demo_nodes_cpp', 'talker'], label='talker')
    wait_until(lambda: ros2(ros, 'param', 'set', '/introspection_service', 'service_configure_introspection',
                            'contents').returncode == 0, 30, 'introspection on')
    # What the recorder is sent, seen by the probe as well (subscribed first: it must not join the
    # graph while the recorder discovers it).
    chatter = ros.probe.collect(String, '/chatter')
    service_events = ros.probe.collect(AddTwoInts.Event, '/add_two_ints/_service_event')
    record = ros.command(['ros2', 'bag', 'record', '-a', '-o', 'everything'], label='record',
                         cwd=str(tmp_path))
    record.wait_for(r"Subscribed to topic '/add_two_ints/_service_event'", timeout=20)
    record.wait_for(r"Subscribed to topic '/chatter'", timeout=20)
    subscribed = len(chatter), len(service_events)

    def recorded_for_sure() -> bool:
        """Two of each kind sent since the recorder subscribed: the first is in the bag by the second."""
        kinds = [event.info.event_type for event in service_events[subscribed[1]:]]
        return len(chatter) - subscribed[0] >= 2 and kinds.count(1) >= 2 and kinds.count(2) >= 2

    wait_until(recorded_for_sure, 20, 'two chatter messages and two requests answered, while recording')
    # And the events of one more request (0.5 s apart): the recorder has taken what came before them.
    seen = len(service_events)
    wait_until(lambda: len(service_events) >= seen + 2, 20, 'one more request answered, while recording')
    record.stop_cleanly()
    bag = tmp_path / 'everything'
    metadata = yaml.safe_load((bag / 'metadata.yaml').read_text())['rosbag2_bagfile_information']
    assert metadata['version'] == 9
    assert metadata['storage_identifier'] == 'mcap'
    assert metadata['relative_file_paths'] == ['everything_0.mcap']
    topics = {t['topic_metadata']['name']: t for t in metadata['topics_with_message_count']}
    assert '/rosout' not in topics
    assert '/parameter_events' not in topics
    chatter = topics['/chatter']['topic_metadata']
    assert chatter['type'] == 'std_msgs/msg/String'
    assert chatter['serialization_format'] == 'cdr'
    assert chatter['type_description_hash'].startswith('RIHS01_')
    assert chatter['offered_qos_profiles'][0]['reliability'] == 'reliable'
    decoded: dict[str, list] = {}
    factory = DecoderFactory()
    with open(bag / 'everything_0.mcap', 'rb') as stream:
        reader = make_reader(stream)
        assert reader.get_header().profile == 'ros2'
        for schema, channel, message in reader.iter_messages():
            assert schema is not None
            assert schema.encoding == 'ros2msg'
            assert channel.message_encoding == 'cdr'
            # mcap-ros2-support 0.6.0 refuses '_' in a type name, so service events are read with rclpy.
            if schema.name.endswith('_Event'):
                found = deserialize_message(message.data, import_type(schema.name))
            else:
                decode = factory.decoder_for(channel.message_encoding, schema)
                assert decode is not None
                found = decode(message.data)
            decoded.setdefault(channel.topic, []).append(found)
    assert {name: len(found) for name, found in decoded.items()} == {
        name: t['message_count'] for name, t in topics.items()}
    assert all(re.fullmatch(r'Hello World: \d+', m.data) for m in decoded['/chatter'])
    events = decoded['/add_two_ints/_service_event']
    assert {(e.info.event_type, tuple((r.a, r.b) for r in e.request), tuple(r.sum for r in e.response))
            for e in events} >= {(1, ((2, 3),), ()), (2, (), (5,))}
    info = ros2(ros, 'bag', 'info', str(bag)).stdout
    assert re.search(r'^Service: +1$', info, re.M), info
    events = topics['/add_two_ints/_service_event']['message_count']
    assert f'Service information: Service: /add_two_ints | Type: example_interfaces/srv/AddTwoInts | ' \
           f'Event Count: {events} | Serialization Format: cdr' in info, info
    assert f"Messages:          {metadata['message_count'] - events}\n" in info, info


@pytest.mark.parametrize(('args', 'message'), [
    (['record'], 'Must specify topic(s)'),
    (['record', '-o', 'exists', '/chatter'], "Output folder 'exists' already exists."),
    (['record', '-s', 'sqlite3', '/chatter'], "Invalid storage 'sqlite3'"),
    (['record', '-e', '(', '-o', 'x'], "argument -e/--regex: '(' is not a regular expression"),
    (['info', 'nowhere'], "No bag at 'nowhere': not a folder"),
    (['info', 'exists'], "No bag at 'exists': it has no metadata.yaml"),
    (['info', 'broken'], "'broken/metadata.yaml' is not rosbag2 metadata"),
    (['play', 'nowhere'], "No bag at 'nowhere': not a folder"),
    (['play', '-r', '0', 'exists'], 'argument -r/--rate: 0 is not a positive number'),
    (['play', '--remap', 'nothing', '--', 'exists'], "argument --remap/-m: 'nothing' is not a remapping"),
])
def test_bag_bad_input_one_line(tmp_path: Path, args: list[str], message: str):
    (tmp_path / 'exists').mkdir()
    (tmp_path / 'broken').mkdir()
    (tmp_path / 'broken' / 'metadata.yaml').write_text('rosbag2_bagfile_information: [not, a, mapping')
    result = subprocess.run(['ros2', 'bag', *args], cwd=tmp_path, capture_output=True, text=True,
                            timeout=TIMEOUT, check=False)
    assert result.returncode in (1, 2), result
    assert 'Traceback' not in result.stderr
    assert message in result.stderr.strip().splitlines()[-1], result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ['broken', 'exists']  # nothing written
