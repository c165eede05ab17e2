"""olive_imu's imu_turtle over real DDS: how the IMU's tilt drives the turtle, alone and launched.

Which IMU tilt drives the turtle which way, the launch file, the scripted IMU driving it around, bad
input, Ctrl-C.
"""

import math
import re
import signal
import time

import pytest
from geometry_msgs.msg import Quaternion, Twist
from olive_imu.imu_turtle import PUBLISH_PERIOD
from owl_common import quaternion as quat
from ros_harness import wait_for_messages, wait_for_quiet, wait_until
from sensor_msgs.msg import Imu
from turtlesim.msg import Pose

IMU_NODE = 'olive_imu_x1684267976913_dcm_srv'
IMU_TOPIC = '/olive/imu/x1684267976913/imu'
CMD_VEL = '/turtle1/cmd_vel'
WINDOW = 11.088889
START = WINDOW / 2
TURTLE_QOS = 7


def start_turtle_and_imu(ros, *imu_turtle_args):
    """turtlesim, imu_sim taking its orientation from ~/true_orientation, and imu_turtle."""
    ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=command')
    turtlesim = ros.run('turtlesim', 'turtlesim_node', '--headless')
    turtlesim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    imu_turtle = ros.run('olive_imu', 'imu_turtle', *imu_turtle_args)
    ros.probe.wait_for_node(IMU_NODE, timeout=30)
    ros.probe.wait_for_node('imu_turtle', timeout=30)
    return turtlesim, imu_turtle


def commander(ros):
    """A function that turns the simulated IMU to roll, pitch, yaw (rad)."""
    publisher = ros.probe.node.create_publisher(Quaternion, f'/{IMU_NODE}/true_orientation', 10)
    wait_until(lambda: publisher.get_subscription_count() > 0, 20, 'true_orientation subscriber')

    def turn(roll, pitch, yaw):
        x, y, z, w = quat.from_euler(roll, pitch, yaw)
        publisher.publish(Quaternion(x=x, y=y, z=z, w=w))
    return turn


def settle(twists, linear, angular, timeout=20.0):
    """Wait until imu_turtle commands about this velocity (imu_sim turns at 3 rad/s, plus noise)."""
    wait_until(lambda: twists and abs(twists[-1].linear.x - linear) < 0.02
               and abs(twists[-1].angular.z - angular) < 0.02, timeout,
               f'linear.x {linear} and angular.z {angular} (last: {twists[-1] if twists else None})')


def rolled(imu: list[Imu], roll: float) -> bool:
    """Whether the IMU's last message says it is rolled about this much (rad)."""
    if not imu:
        return False
    q = imu[-1].orientation
    euler = quat.usable_euler((q.x, q.y, q.z, q.w))
    return euler is not None and abs(euler[0] - roll) < 0.05


def test_tilting_the_imu_forward_drives_the_turtle_forward_and_turning_it_left_turns_it_left(ros):
    _, imu_turtle = start_turtle_and_imu(ros)
    probe = ros.probe
    twists = probe.collect(Twist, CMD_VEL)
    poses = probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    imu = probe.collect(Imu, IMU_TOPIC)
    turn = commander(ros)
    imu_turtle.wait_for(rf'IMU data on {IMU_TOPIC}: driving {CMD_VEL}', timeout=20)
    settle(twists, 0.0, 0.0)  # level and facing ahead: standing
    turn(0.4, 0.0, 0.0)       # roll does not drive
    wait_until(lambda: rolled(imu, 0.4), 10, 'the IMU rolled to 0.4 rad')
    seen = len(twists)
    wait_for_messages(twists, seen + 5, what='velocities while the IMU is rolled')
    assert all(abs(t.linear.x) < 0.02 and abs(t.angular.z) < 0.02 for t in twists[seen:]), twists[seen:]

    turn(0.0, 0.3, 0.0)  # nose down: REP 103 pitch +0.3
    settle(twists, 1.5 * 0.3, 0.0)
    x = poses[-1].x
    wait_until(lambda: poses[-1].x > x + 0.2, 10, 'the turtle moving forward (+x, it faces east)')
    assert abs(poses[-1].theta) < 0.05

    turn(0.0, -0.3, 0.0)  # nose up: backward
    settle(twists, -1.5 * 0.3, 0.0)
    x = poses[-1].x
    wait_until(lambda: poses[-1].x < x - 0.2, 10, 'the turtle moving backward')

    turn(0.0, 0.0, 0.5)  # turned left: the turtle turns left, counter-clockwise
    settle(twists, 0.0, 1.5 * 0.5)
    theta = poses[-1].theta
    wait_until(lambda: poses[-1].theta > theta + 0.3, 10, 'the turtle turning left')

    turn(0.0, 0.0, -0.5)
    settle(twists, 0.0, -1.5 * 0.5)
    theta = poses[-1].theta
    wait_until(lambda: poses[-1].theta < theta - 0.3, 10, 'the turtle turning right')
    imu_turtle.stop_cleanly()
    assert 'Traceback' not in imu_turtle.output


def test_speed_factors_change_at_runtime_and_bad_values_are_refused_with_a_reason(ros):
    start_turtle_and_imu(ros, '--ros-args', '-p', 'speed_factor:=2.0', '-p', 'turn_factor:=0.5')
    probe = ros.probe
    twists = probe.collect(Twist, CMD_VEL)
    turn = commander(ros)
    turn(0.0, 0.2, 0.4)
    settle(twists, 2.0 * 0.2, 0.5 * 0.4)
    assert all(r.successful for r in probe.set_parameters('/imu_turtle', speed_factor=1.0, turn_factor=3.0))
    settle(twists, 1.0 * 0.2, 3.0 * 0.4)
    for name, value, reason in (('speed_factor', 10.5, 'out of range'), ('turn_factor', -1.0, 'out of range'),
                                ('speed_factor', 'fast', 'type'), ('speed_factor', 2, 'type'),
                                ('imu_topic', '/elsewhere', 'read-only')):
        [result] = probe.set_parameters('/imu_turtle', **{name: value})
        assert not result.successful, (name, value, result.reason)
        assert reason in result.reason, (name, value, result.reason)
    assert probe.get_parameters('/imu_turtle', 'speed_factor', 'turn_factor', 'imu_topic') == [
        1.0, 3.0, IMU_TOPIC]
    settle(twists, 1.0 * 0.2, 3.0 * 0.4)


@pytest.mark.parametrize(('args', 'message'), [
    (['-p', 'speed_factor:=20.0'], 'out of range'),
    (['-p', 'turn_factor:=fast'], "'turn_factor' to 'fast' of type 'STRING', expecting type 'DOUBLE'"),
    (['-p', 'imu_topic:=my imu'], "imu_topic 'my imu' is not a valid topic name"),
])
def test_bad_startup_parameters_end_with_one_line_and_code_2(ros, args, message):
    imu_turtle = ros.run('olive_imu', 'imu_turtle', '--ros-args', *args)
    assert imu_turtle.wait(30) == 2
    assert imu_turtle.lines == [line for line in imu_turtle.lines if line.startswith('imu_turtle: error: ')]
    assert len(imu_turtle.lines) == 1, imu_turtle.output
    assert message in imu_turtle.output, imu_turtle.output


def imu_message(x=0.0, y=0.0, z=0.0, w=1.0, covariance=0.0):
    msg = Imu()
    msg.orientation = Quaternion(x=x, y=y, z=z, w=w)
    msg.orientation_covariance[0] = covariance
    return msg


def publish_for(publisher, msg, seconds):
    """Publish msg at 100 Hz, as an IMU does."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        publisher.publish(msg)
        time.sleep(0.01)


def publish_until(publisher, msg, done, what, timeout=10.0):
    """Publish msg at 100 Hz, as an IMU does, until done() is true."""
    deadline = time.monotonic() + timeout
    while not done():
        if time.monotonic() > deadline:
            raise AssertionError(f'timed out after {timeout} s publishing until {what}')
        publisher.publish(msg)
        time.sleep(0.01)


def said(process, pattern):
    """A done() for publish_until: whether the process has printed a line matching the regex pattern."""
    return lambda: any(re.search(pattern, line) for line in list(process.lines))


def test_it_names_the_topic_it_waits_for_and_ignores_unusable_orientations_with_a_throttled_warning(ros):
    imu_turtle = ros.run('olive_imu', 'imu_turtle', '--ros-args', '-p', 'imu_topic:=/test_imu')
    imu_turtle.wait_for(r'waiting for IMU messages on /test_imu \(0 publisher\(s\) so far\)', timeout=30)
    probe = ros.probe
    twists = probe.collect(Twist, CMD_VEL)
    imu = probe.node.create_publisher(Imu, '/test_imu', 10)
    wait_until(lambda: imu.get_subscription_count() > 0, 20, 'imu_turtle subscribing to /test_imu')

    publish_for(imu, imu_message(x=math.nan), 1.0)
    imu_turtle.wait_for(r'IMU message ignored: the orientation quaternion \(nan, 0.0, 0.0, 1.0\) is not fin')
    # throttled: one line (two when a busy machine spread their handling past the 2 s), not 100
    assert len([line for line in imu_turtle.lines if 'IMU message ignored' in line]) in (1, 2)
    # The other kinds, each until its warning: the first one after the throttle's 2 s is said.
    for msg, warning in ((imu_message(w=0.0), 'the orientation quaternion is zero, not a rotation'),
                         (imu_message(covariance=-1.0), 'the IMU reports no orientation')):
        publish_until(imu, msg, said(imu_turtle, f'IMU message ignored: {re.escape(warning)}'), warning)
    # Still waiting, and it counts this test's publisher. That line comes every 5 s: looked for after
    # the unusable messages, not waited for before them.
    imu_turtle.wait_for(r'waiting for IMU messages on /test_imu \(1 publisher\(s\) so far\)', timeout=15)
    assert twists == []  # never driven by an unusable orientation

    usable = imu_message(*quat.from_euler(0.0, 0.2, 0.0))
    publish_until(imu, usable, lambda: twists and twists[-1].linear.x == pytest.approx(0.3),
                  'driving at 0.3 m/s')
    imu_turtle.wait_for(r'no usable IMU message on /test_imu for 0.5 s: the turtle stops', timeout=10)
    count = wait_for_quiet(twists, 5 * PUBLISH_PERIOD, what='velocities after the stale warning')
    time.sleep(0.5)
    assert len(twists) == count  # stale: no more commands
    # and the node is alive: a usable message drives again
    publish_until(imu, usable, lambda: len(twists) > count, 'a velocity once the IMU is back')
    imu_turtle.stop_cleanly()
    assert 'Traceback' not in imu_turtle.output


def test_the_launch_file_starts_turtlesim_and_imu_turtle_with_its_arguments(ros):
    ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=command')
    launch = ros.command(['ros2', 'launch', 'olive_imu', 'imu_turtle.launch.py', 'speed_factor:=1.0'],
                         label='imu_turtle.launch')
    launch.wait_for(r'\[turtlesim_node-1\].*Spawning turtle \[turtle1\]', timeout=30)
    probe = ros.probe
    probe.wait_for_node('imu_turtle', timeout=30)
    assert probe.get_parameters('/imu_turtle', 'speed_factor', 'turn_factor', 'imu_topic') == [
        1.0, 1.5, IMU_TOPIC]
    poses = probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    turn = commander(ros)
    turn(0.0, 0.4, 0.0)
    wait_for_messages(poses, 1)
    wait_until(lambda: poses[-1].x > START + 0.3, 20, 'the turtle driving forward')
    assert poses[-1].linear_velocity == pytest.approx(0.4, abs=0.02)
    launch.send_signal(signal.SIGINT)
    assert launch.wait(30) == 0
    assert launch.output.count('process has finished cleanly') == 2, launch.output
    assert 'Traceback' not in launch.output


def test_the_scripted_imu_drives_the_turtle_around_inside_the_window(ros):
    """Issue 11 item 4: with olive_sim's default IMU motion the turtle loops around its start."""
    ros.run('olive_sim', 'imu_sim')
    turtlesim = ros.run('turtlesim', 'turtlesim_node', '--headless')
    turtlesim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    poses = ros.probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    imu_turtle = ros.run('olive_imu', 'imu_turtle')
    imu_turtle.wait_for(r'IMU data on .*: driving', timeout=30)
    count = len(poses)

    def spans() -> tuple[float, float]:
        path = poses[count:]
        if not path:
            return 0.0, 0.0
        xs, ys = [p.x for p in path], [p.y for p in path]
        return max(xs) - min(xs), max(ys) - min(ys)

    # The scripted motion loops the turtle in about 20 s; on a slow machine it takes longer.
    wait_until(lambda: min(spans()) > 1.5, 60, f'the turtle looping over 1.5 m each way (so far {spans()})')
    path = poses[count:]
    xs, ys = [p.x for p in path], [p.y for p in path]
    assert sum(abs(p.linear_velocity) for p in path) / len(path) > 0.3  # m/s on average
    assert 0.5 < min(xs)
    assert max(xs) < WINDOW - 0.5
    assert 0.5 < min(ys)
    assert max(ys) < WINDOW - 0.5
    assert 'hit the wall' not in turtlesim.output
