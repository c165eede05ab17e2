"""The course's chapter 3 `ros2` command sequence against our turtlesim, as the course shows it.

Differences from the course text, which was written for Humble: nodes also offer the Jazzy+
`get_type_description` service and `start_type_description_service` parameter, and the course
elides some blank lines; everything else is compared line by line.
"""

import re
import subprocess

import pytest
from ros_harness import RosHarness

TURTLESIM_SERVICES = [
    ('/clear', 'std_srvs/srv/Empty'), ('/kill', 'turtlesim/srv/Kill'), ('/reset', 'std_srvs/srv/Empty'),
    ('/spawn', 'turtlesim/srv/Spawn'), ('/turtle1/set_pen', 'turtlesim/srv/SetPen'),
    ('/turtle1/teleport_absolute', 'turtlesim/srv/TeleportAbsolute'),
    ('/turtle1/teleport_relative', 'turtlesim/srv/TeleportRelative'),
    ('/turtlesim/describe_parameters', 'rcl_interfaces/srv/DescribeParameters'),
    ('/turtlesim/get_parameter_types', 'rcl_interfaces/srv/GetParameterTypes'),
    ('/turtlesim/get_parameters', 'rcl_interfaces/srv/GetParameters'),
    ('/turtlesim/get_type_description', 'type_description_interfaces/srv/GetTypeDescription'),
    ('/turtlesim/list_parameters', 'rcl_interfaces/srv/ListParameters'),
    ('/turtlesim/set_parameters', 'rcl_interfaces/srv/SetParameters'),
    ('/turtlesim/set_parameters_atomically', 'rcl_interfaces/srv/SetParametersAtomically'),
]


def ros2(sandbox, *args):
    result = subprocess.run(['ros2', *args], env=sandbox.env, capture_output=True, text=True, timeout=60,
                            check=False)
    assert 'Traceback' not in result.stderr
    return result


def lines(result):
    return result.stdout.splitlines()


@pytest.fixture(scope='module')
def turtlesim():
    harness = RosHarness()
    try:
        harness.command(['ros2', 'run', 'turtlesim', 'turtlesim_node'], label='turtlesim')
        assert ros2(harness, 'daemon', 'start').returncode == 0
        for _ in range(100):
            if lines(ros2(harness, 'node', 'list')) == ['/turtlesim'] and \
                    len(lines(ros2(harness, 'service', 'list'))) == len(TURTLESIM_SERVICES):
                break
        yield harness
    finally:
        ros2(harness, 'daemon', 'stop')
        harness.close()


def test_nodes_and_topics(turtlesim):
    assert lines(ros2(turtlesim, 'node', 'list')) == ['/turtlesim']
    info = lines(ros2(turtlesim, 'node', 'info', '/turtlesim'))
    assert info == [
        '/turtlesim',
        '  Subscribers:',
        '    /parameter_events: rcl_interfaces/msg/ParameterEvent',
        '    /turtle1/cmd_vel: geometry_msgs/msg/Twist',
        '  Publishers:',
        '    /parameter_events: rcl_interfaces/msg/ParameterEvent',
        '    /rosout: rcl_interfaces/msg/Log',
        '    /turtle1/color_sensor: turtlesim/msg/Color',
        '    /turtle1/pose: turtlesim/msg/Pose',
        '  Service Servers:',
        *[f'    {name}: {srv_type}' for name, srv_type in TURTLESIM_SERVICES],
        '  Service Clients:',
        '',
        '  Action Servers:',
        '    /turtle1/rotate_absolute: turtlesim/action/RotateAbsolute',
        '  Action Clients:',
        '']
    assert lines(ros2(turtlesim, 'topic', 'info', '/turtle1/cmd_vel')) == [
        'Type: geometry_msgs/msg/Twist', 'Publisher count: 0', 'Subscription count: 1']


def test_publish_and_echo_cmd_vel(turtlesim):
    echo = turtlesim.command(['ros2', 'topic', 'echo', '/turtle1/cmd_vel'], label='echo')
    pose_before = ros2(turtlesim, 'topic', 'echo', '--once', '/turtle1/pose').stdout
    for _ in range(100):  # until the echo's subscription is in the graph
        if 'Subscription count: 2' in ros2(turtlesim, 'topic', 'info', '/turtle1/cmd_vel').stdout:
            break
    # -w 2: turtlesim and the echo both hear it
    pub = ros2(turtlesim, 'topic', 'pub', '-1', '-w', '2', '--max-wait-time-secs', '30', '/turtle1/cmd_vel',
               'geometry_msgs/msg/Twist',
               '{linear: {x: 2}, angular: {z: 1}}')
    assert pub.returncode == 0
    assert [line for line in lines(pub) if not line.startswith('Waiting for')][:2] == [
        'publisher: beginning loop',
        'publishing #1: geometry_msgs.msg.Twist(linear=geometry_msgs.msg.Vector3(x=2.0, y=0.0, z=0.0), '
        'angular=geometry_msgs.msg.Vector3(x=0.0, y=0.0, z=1.0))']
    echo.wait_for('^---$', timeout=20)
    assert echo.lines[:9] == ['linear:', '  x: 2.0', '  y: 0.0', '  z: 0.0', 'angular:', '  x: 0.0',
                              '  y: 0.0', '  z: 1.0', '---']
    assert ros2(turtlesim, 'topic', 'echo', '--once', '/turtle1/pose').stdout != pose_before
    # Stopped here: the module's later tests share this turtlesim and count its subscribers.
    assert echo.stop() == 2, echo.tail()  # Ctrl-C: exit code 2 (SIGINT's number), as upstream


def test_services(turtlesim):
    assert lines(ros2(turtlesim, 'service', 'list')) == [name for name, _ in TURTLESIM_SERVICES]
    assert lines(ros2(turtlesim, 'service', 'type', '/clear')) == ['std_srvs/srv/Empty']
    assert lines(ros2(turtlesim, 'service', 'list', '-t')) == [f'{n} [{t}]' for n, t in TURTLESIM_SERVICES]
    assert lines(ros2(turtlesim, 'interface', 'show', 'std_srvs/srv/Empty')) == ['---']
    spawn_definition = lines(ros2(turtlesim, 'interface', 'show', 'turtlesim/srv/Spawn'))
    assert spawn_definition[:3] == ['float32 x', 'float32 y', 'float32 theta']
    assert spawn_definition[-2:] == ['---', 'string name']
    assert any(line.startswith('string name') for line in spawn_definition[3:-2])
    clear = ros2(turtlesim, 'service', 'call', '/clear', 'std_srvs/srv/Empty')
    assert [line for line in lines(clear) if not line.startswith('waiting')] == [
        'requester: making request: std_srvs.srv.Empty_Request()', '', 'response:',
        'std_srvs.srv.Empty_Response()', '']
    spawn = ros2(turtlesim, 'service', 'call', '/spawn', 'turtlesim/srv/Spawn',
                 "{x: 1.0, y: 1.0, name: 'olive_turtle'}")
    assert [line for line in lines(spawn) if not line.startswith('waiting')] == [
        'requester: making request: '
        "turtlesim.srv.Spawn_Request(x=1.0, y=1.0, theta=0.0, name='olive_turtle')",
        '', 'response:', "turtlesim.srv.Spawn_Response(name='olive_turtle')", '']
    topics = lines(ros2(turtlesim, 'topic', 'list'))
    assert '/olive_turtle/cmd_vel' in topics
    assert '/olive_turtle/pose' in topics


def test_parameters_and_file_round_trip(turtlesim, tmp_path):
    listing = lines(ros2(turtlesim, 'param', 'list'))
    assert listing[:4] == ['/turtlesim:', '  background_b', '  background_g', '  background_r']
    assert lines(ros2(turtlesim, 'param', 'get', '/turtlesim', 'background_r')) == ['Integer value is: 69']
    assert lines(ros2(turtlesim, 'param', 'get', '/turtlesim', 'background_g')) == ['Integer value is: 86']
    assert lines(ros2(turtlesim, 'param', 'get', '/turtlesim', 'background_b')) == ['Integer value is: 255']
    assert lines(ros2(turtlesim, 'param', 'set', '/turtlesim', 'background_r', '255')) == \
        ['Set parameter successful']
    dump = ros2(turtlesim, 'param', 'dump', '/turtlesim').stdout
    assert dump.startswith('/turtlesim:\n  ros__parameters:\n    background_b: 255\n    background_g: 86\n'
                           '    background_r: 255\n    qos_overrides:\n      /parameter_events:\n')
    saved = tmp_path / 'turtlesim.yaml'
    saved.write_text(dump.replace('background_b: 255', 'background_b: 0').replace(
        'background_g: 86', 'background_g: 0').replace('background_r: 255', 'background_r: 0'))
    load = ros2(turtlesim, 'param', 'load', '/turtlesim', str(saved))
    assert 'Set parameter background_r successful' in lines(load)
    assert ros2(turtlesim, 'param', 'dump', '/turtlesim').stdout == saved.read_text()


def test_actions(turtlesim):
    # (test_services spawned olive_turtle, which has its own rotate_absolute)
    assert '/turtle1/rotate_absolute [turtlesim/action/RotateAbsolute]' in \
        lines(ros2(turtlesim, 'action', 'list', '-t'))
    assert lines(ros2(turtlesim, 'action', 'info', '/turtle1/rotate_absolute')) == [
        'Action: /turtle1/rotate_absolute', 'Action clients: 0', 'Action servers: 1', '    /turtlesim']
    assert lines(ros2(turtlesim, 'interface', 'show', 'turtlesim/action/RotateAbsolute')) == [
        '# The desired heading in radians', 'float32 theta', '---',
        '# The angular displacement in radians to the starting position', 'float32 delta', '---',
        '# The remaining rotation in radians', 'float32 remaining']
    goal = ros2(turtlesim, 'action', 'send_goal', '/turtle1/rotate_absolute',
                'turtlesim/action/RotateAbsolute', '{theta: 1.5}', '--feedback')
    assert goal.returncode == 0, goal.stderr
    output = lines(goal)
    assert output[:4] == ['Waiting for an action server to become available...', 'Sending goal:',
                          '     theta: 1.5', '']
    assert re.fullmatch('Goal accepted with ID: [0-9a-f]{32}', output[4])
    assert 'Feedback:' in output
    assert re.fullmatch(r'    remaining: -?\d+\.\d+(e-\d+)?', output[output.index('Feedback:') + 1])
    result = output.index('Result:')
    assert re.fullmatch(r'    delta: -?\d+\.\d+', output[result + 1])
    assert output[-1] == 'Goal finished with status: SUCCEEDED'
