"""A ROS 2 Humble module beside our Jazzy processes, on the wire.

humble_twin (src/common/owl_humble, the IMU here) and humble_fastdds_twin
(src/common/owl_humble_fastdds, the servo, on real Fast DDS with its torque services) are what a
Humble Olive module sends: graph messages with 24-byte gids, endpoints without type hashes. Beside
them run the simulated kit, the course's chapter 4 nodes and the `ros2` command, in each network
mode. A twin counts every graph message it receives that a Humble module would misread; with our
Fast DDS profile there is none, and without the profile's ros_discovery_info partition there are
many (so the count can fail the test).
"""

import re
import signal
import subprocess
import time
from pathlib import Path

import pytest
from owl_common.processes import RosSandbox
from ros_harness import wait_until
from turtlesim_py.world import CENTER

ROOT = Path(__file__).resolve().parent.parent
PROFILE = ROOT / 'config' / 'fastdds.xml'
IMU_NODE = '/olive_imu_humble_dcm_srv'
SERVO_NODE = '/olive_servo_humble_dcm_srv'
KIT_NODES = ('/olive_imu_x1684267976913_dcm_srv', '/olive_servo_pan_dcm_srv', '/olive_servo_tilt_dcm_srv',
             '/olive_camera_eye_dcm_srv')
RANGES = {'private': 'LOCALHOST', 'open': 'SUBNET'}
# s from the twins' "ready" to the first `ros2 node list` naming both. In private mode the IMU twin is
# ready once the bridge it starts has forwarded it. In open mode our tools' bridge (Cyclone DDS) learns
# of a Fast DDS participant that came up after it only from that participant's next periodic
# announcement (every 3 s on Fast DDS's defaults, a real module's too), not from its first ones:
# the Fast DDS servo was named 2.9-3.8 s after it was ready on a quiet machine, the Cyclone twin at once.
FASTDDS_ANNOUNCEMENT_PERIOD = 3.0
LISTED_WITHIN = {'private': 2.0, 'open': 2 * FASTDDS_ANNOUNCEMENT_PERIOD}  # a listing call takes 1 s too
NO_DISPLAY = {'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1'}
SUMMARY = r"discovery samples received: (\d+), malformed in Humble's layout: (\d+)"


def ros2(sandbox, *args, env=None, timeout=30.0):
    result = subprocess.run(['ros2', *args], env={**sandbox.env, **(env or {})}, capture_output=True,
                            text=True, timeout=timeout, check=False)
    assert 'Traceback' not in result.stderr, result.stderr
    return result


def node_list(sandbox):
    return set(ros2(sandbox, 'node', 'list').stdout.split())


def unprotected_profile(tmp_path):
    """config/fastdds.xml without the ros_discovery_info profiles: a Jazzy graph as upstream's."""
    text = PROFILE.read_text()
    stripped = re.sub(r'\s*<data_(writer|reader) profile_name="ros_discovery_info">.*?</data_\1>', '',
                      text, flags=re.S)
    assert 'ros_discovery_info"' not in stripped, 'the profile has no graph partition'
    assert stripped != text, 'the profile has no graph partition'
    path = tmp_path / 'unprotected.xml'
    path.write_text(stripped)
    return str(path)


def stop_twin(twin):
    """Ctrl-C the twin; (graph messages it received, malformed ones) from its last line."""
    twin.send_signal(signal.SIGINT)
    assert twin.wait(10) == 0, twin.tail()
    received, malformed = twin.wait_for(SUMMARY)[0].groups()
    return int(received), int(malformed)


def seconds_until_listing(sandbox, condition, timeout=10.0):
    """When the first `ros2 node list` whose answer meets the condition began (s from now), and that answer.

    Each call takes a while itself; what counts is when it was asked.
    """
    started = time.monotonic()
    while time.monotonic() < started + timeout:
        asked = time.monotonic()
        if condition(names := node_list(sandbox)):
            return asked - started, names
    raise AssertionError(f'no ros2 node list within {timeout} s met the condition: {node_list(sandbox)}')


def turtle_x(sandbox):
    out = ros2(sandbox, 'topic', 'echo', '/turtle1/pose', '--once').stdout
    x = re.search(r'^x: (\S+)', out, re.M)
    assert x, out
    return float(x.group(1))


@pytest.mark.parametrize('network', sorted(RANGES))
@pytest.mark.whole_kit
def test_a_humble_module_beside_the_kit_and_chapter_4_nodes_is_safe_listed_and_talked_to(network):
    with RosSandbox(discovery_range=RANGES[network]) as sandbox:
        kit = sandbox.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py', 'web_port:=0'],
                              label='kit')
        robot = sandbox.command(['ros2', 'launch', 'olive_camera', 'robot_camera.launch.py'], env=NO_DISPLAY,
                                label='robot_camera')
        turtlesim = sandbox.run('turtlesim', 'turtlesim_node', '--headless')
        robot.wait_for(r'\[imu_control_robot-1\].*torque enabled: pan, tilt', timeout=60)
        turtlesim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
        wait_until(lambda: set(KIT_NODES) <= node_list(sandbox), 30, 'the kit in ros2 node list')

        imu = sandbox.run('owl_humble', 'humble_twin', '--module', 'imu', label='humble imu')
        # The servo on real Fast DDS, so that owl network --kit's setTorqueEnable call is answered as a
        # real module answers it (2 s for a new client's reader, as our own servers: see test_humble_fastdds).
        servo = sandbox.run('owl_humble_fastdds', 'humble_fastdds_twin', '--reply-wait', '2',
                            label='humble servo')
        imu.wait_for('ready: node ' + IMU_NODE, timeout=20)
        servo.wait_for('ready: node ' + SERVO_NODE, timeout=20)
        # Goals -> the twin's servo, which follows them in its joint state. The goal goes out while the
        # twins are listed; not before the twin is ready: a goal sent while it still starts can be lost.
        goal = sandbox.command(['ros2', 'topic', 'pub', '-1', '-w', '1', '/olive/servo/humble/goal/position',
                                'std_msgs/msg/Float32', '{data: 0.5}'], label='ros2 topic pub')
        # Section 4.4: nothing moves before setTorqueEnable (the twin holds the goal until then).
        enable = sandbox.command(['ros2', 'service', 'call', '/olive/servo/humble/setTorqueEnable',
                                  'std_srvs/srv/Trigger'], label='ros2 service call')
        listed_after, _ = seconds_until_listing(sandbox, lambda names: {IMU_NODE, SERVO_NODE} <= names)
        assert listed_after <= LISTED_WITHIN[network], \
            f'the first call to list the Humble nodes began {listed_after:.2f} s after they started'

        # IMU -> the course's imu_turtle: the twin's fixed 0.3 rad pitch drives the turtle forward. Started
        # now, it comes up while the servo gets its goal.
        imu_turtle = sandbox.run('olive_imu', 'imu_turtle', '--ros-args',
                                 '-p', 'imu_topic:=/olive/imu/humble/imu')
        goal.wait(30)
        assert 'Traceback' not in goal.output, goal.output
        enable.wait(30)
        assert "Trigger_Response(success=True, message='torque enabled')" in enable.output, enable.output
        servo.wait_for(r'goal \+0\.500 rad on /olive/servo/humble/goal/position', timeout=10)
        # owl network --kit: every module with its distribution, one message each way. It mostly waits
        # (discovery, acknowledgements: about 10 s), so the `ros2` checks below run meanwhile; it starts
        # once the servo has the goal, as it reports the position the servo has then.
        check = sandbox.command(['owl', 'network', '--kit', '--discovery-time', '2'], label='owl network')
        joint = ros2(sandbox, 'topic', 'echo', '/olive/servo/humble/joint', '--once').stdout
        assert re.search(r'position:\n- 0\.5', joint), joint
        info = ros2(sandbox, 'topic', 'info', '-v', '/olive/imu/humble/imu').stdout
        assert f'Node name: {IMU_NODE[1:]}' in info, info
        assert 'Topic type hash: INVALID' in info, info
        assert '/olive/imu/humble/imu' in ros2(sandbox, 'node', 'info', IMU_NODE).stdout

        imu_turtle.wait_for('IMU data on /olive/imu/humble/imu: driving /turtle1/cmd_vel', timeout=20)
        # From the spawn point, not from a first reading: at 0.45 m/s the turtle reaches the east wall
        # about 12 s after it starts, and a first reading that a loaded suite's slow `ros2` calls delay
        # can come from there, after which x grows no more.
        try:
            wait_until(lambda: turtle_x(sandbox) > CENTER + 0.3, 15,
                       'the turtle driven forward by the Humble IMU')
        except AssertionError as failure:
            cmd_vel = ros2(sandbox, 'topic', 'info', '-v', '/turtle1/cmd_vel').stdout
            raise AssertionError(f'{failure}; x is {turtle_x(sandbox)}\n/turtle1/cmd_vel:\n{cmd_vel}'
                                 f'\nimu_turtle:\n{imu_turtle.tail()}\nturtlesim:\n{turtlesim.tail()}'
                                 f'\nhumble imu:\n{imu.tail()}') from None

        check.wait(90)
        lines = check.output
        assert 'Traceback' not in lines, lines
        assert (f'ok: imu humble ({IMU_NODE}, ROS 2 Humble): one Imu on /olive/imu/humble/imu from it, '
                'one Bool (LED on) on /olive/imu/humble/led to it') in lines, lines
        assert re.search(rf'ok: servo humble \({SERVO_NODE}, ROS 2 Humble\): one JointState on '
                         r'/olive/servo/humble/joint from it, one goal of \+0\.500 rad \(its position\) on '
                         r"/olive/servo/humble/goal/position to it; setTorqueEnable answered in \d+ ms "
                         r"\('torque already enabled'\), torque left on", lines), lines
        assert 'ok: servo pan (/olive_servo_pan_dcm_srv, ROS 2 Iron or newer): one JointState' in lines, lines
        assert ('ok: camera eye (/olive_camera_eye_dcm_srv, ROS 2 Iron or newer): one CompressedImage'
                in lines), lines
        assert 'ok: Humble modules are safe beside this shell' in lines, lines
        imu.wait_for('LED on', timeout=5)

        assert stop_twin(imu)[1] == 0, imu.output
        gone_after, names = seconds_until_listing(sandbox, lambda names: IMU_NODE not in names)
        assert gone_after <= 5.0, f'the Humble IMU was listed by calls up to {gone_after:.2f} s after it left'
        assert SERVO_NODE in names, names
        assert stop_twin(servo)[1] == 0, servo.output
        # The robot before the kit: stopping, imu_control_robot switches the servos' torque off through the
        # kit (with the kit gone it waits 3.5 s for answers).
        for process in (imu_turtle, robot, turtlesim):
            process.send_signal(signal.SIGINT)
        assert robot.wait(30) == 0, robot.tail() + kit.tail()
        kit.send_signal(signal.SIGINT)
        assert kit.wait(30) == 0, robot.tail() + kit.tail()


def test_without_the_graph_partition_a_humble_module_gets_messages_it_misreads(tmp_path):
    with RosSandbox() as sandbox:
        twin = sandbox.run('owl_humble', 'humble_twin', '--module', 'servo')
        twin.wait_for('ready: node ' + SERVO_NODE, timeout=20)
        unprotected = {'FASTRTPS_DEFAULT_PROFILES_FILE': unprotected_profile(tmp_path)}
        turtlesim = sandbox.run('turtlesim', 'turtlesim_node', '--headless', env=unprotected)
        turtlesim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
        ros2(sandbox, 'node', 'list', '--no-daemon', env=unprotected)
        twin.wait_for('malformed discovery sample #1 .*Jazzy layout', timeout=20)
        received, malformed = stop_twin(twin)
        assert malformed > 0, twin.output
        assert malformed == received, twin.output


def test_a_stock_jazzy_install_beside_ours_sees_our_topics_not_our_node_names_and_we_see_its_nodes(tmp_path):
    """A student's normal Jazzy (no profile of ours) beside our processes: nothing breaks.

    It lists our topics but not our nodes (our graph messages are in our partition), and our tools list
    its node through the discovery bridge.
    """
    stock_script = tmp_path / 'stock_jazzy.py'
    stock_script.write_text(
        'import time, rclpy\n'
        'rclpy.init()\n'
        "node = rclpy.create_node('stock_jazzy_node')\n"
        'deadline = time.monotonic() + 20\n'
        'while (time.monotonic() < deadline\n'
        "       and '/turtle1/pose' not in dict(node.get_topic_names_and_types())):\n"
        '    rclpy.spin_once(node, timeout_sec=0.1)\n'
        'time.sleep(2)\n'
        "print('topics:', sorted(dict(node.get_topic_names_and_types())), flush=True)\n"
        "print('nodes:', sorted(node.get_node_names()), flush=True)\n"
        'rclpy.spin(node)\n')
    with RosSandbox(discovery_range='SUBNET') as sandbox:  # a stock install is on another machine
        turtlesim = sandbox.run('turtlesim', 'turtlesim_node', '--headless')
        turtlesim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
        stock = sandbox.command(['python', str(stock_script)], label='stock jazzy',
                                env={'FASTRTPS_DEFAULT_PROFILES_FILE': unprotected_profile(tmp_path)})
        topics = stock.wait_for(r'^topics: (.*)', timeout=30)[0].group(1)
        nodes = stock.wait_for(r'^nodes: (.*)', timeout=10)[0].group(1)
        assert "'/turtle1/pose'" in topics
        assert 'turtlesim' not in nodes
        assert 'stock_jazzy_node' in nodes
        wait_until(lambda: {'/stock_jazzy_node', '/turtlesim'} <= node_list(sandbox), 10,
                   'the stock node and ours in our ros2 node list')
        stock.stop(timeout=5)
