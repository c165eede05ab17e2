"""olive_servo over real DDS against olive_sim's servos: its three nodes and their torque handling.

control_servo's sine, the appendix's pid_testing, imu_control_robot; torque on before any goal and
off after Ctrl-C, signs, bounds, bad input.
"""

import math
import threading
import time

import pytest
from geometry_msgs.msg import Quaternion
from owl_common import quaternion as quat
from ros_harness import wait_for_messages, wait_until
from sensor_msgs.msg import Imu
from servo_helpers import (
    BOUNDS,
    COLLECT_DEPTH,
    TORQUE_OFF_WARNING,
    assert_clean_servo,
    collect,
    joint_near,
    start_servo,
    torque_enabled,
)
from std_msgs.msg import Float32
from std_srvs.srv import Trigger

IMU_NODE = 'olive_imu_x1684267976913_dcm_srv'


def test_control_servo_waits_for_the_servo_enables_its_torque_before_any_goal_and_disables_it_at_ctrl_c(ros):
    # The node first, the servo later: a goal sent before the torque is on would reach the servo.
    control_servo = ros.run('olive_servo', 'control_servo')
    control_servo.wait_for(r'waiting for service /olive/servo/pan/setTorqueEnable', timeout=30)
    # Numbered by control_servo's publisher: the probe subscribes 0.5 s before the first goal, and
    # discovery can match it a goal or more late (a run saw the sine start at 0.01).
    goals = ros.probe.collect_with_info(Float32, '/olive/servo/pan/goal/position',
                                         'publication_sequence_number', COLLECT_DEPTH)
    joints = collect(ros, 'pan', 'joint')
    diagnostics = collect(ros, 'pan', 'joint/diagnostics')
    servo = start_servo(ros, 'pan')
    control_servo.wait_for(r'torque enabled: pan', timeout=30)
    wait_for_messages(goals, 100, timeout=30, what='goals')
    # The course's sine: the input grows by 0.01 rad per goal, amplitude 1 rad; it starts at 0 and
    # goes positive, which turns the pan servo to the left (counter-clockwise seen from above). So the
    # n-th goal published is sin(0.01 (n - 1)), whichever goals the probe got.
    numbers = [number for number, _ in goals[:100]]
    assert numbers == sorted(set(numbers)), numbers  # in order
    assert [goal.data for _, goal in goals[:100]] == pytest.approx(
        [math.sin(0.01 * (number - 1)) for number in numbers], abs=1e-6), numbers
    wait_until(lambda: joints and joints[-1].position[0] > 0.5, 20, 'the pan joint turning left past 0.5 rad')
    wait_until(lambda: diagnostics and torque_enabled(diagnostics), 10, 'torque_enabled true')
    assert all(abs(goal.data) <= 1.0 for _, goal in goals)
    control_servo.stop_cleanly(timeout=10)
    assert 'torque disabled: pan' in control_servo.output
    assert 'Traceback' not in control_servo.output
    servo.wait_for(r'\]: torque disabled$', timeout=10)
    count = len(diagnostics)
    wait_until(lambda: len(diagnostics) > count and not torque_enabled(diagnostics), 10,
               'torque_enabled false after Ctrl-C')
    assert_clean_servo(servo)


def test_a_servo_that_answers_late_is_asked_again_until_it_answers(ros):
    """A kit started with the node on a busy machine once took 11 s to answer the first torque request.

    control_servo gave up after 5 s and ended with an error; now it asks again. The stand-in servo
    here answers its first request only once the node has asked again, and the next at once.
    """
    enable_requests = []
    asked_again = threading.Event()

    def enable_late_at_first(request, response):
        enable_requests.append(request)
        if len(enable_requests) == 1:
            asked_again.wait(timeout=30)
        response.success = True
        return response

    def disable(request, response):
        response.success = True
        return response

    ros.probe.node.create_service(Trigger, '/olive/servo/pan/setTorqueEnable', enable_late_at_first)
    ros.probe.node.create_service(Trigger, '/olive/servo/pan/setTorqueDisable', disable)
    control_servo = ros.run('olive_servo', 'control_servo')
    try:
        control_servo.wait_for(r'/olive/servo/pan/setTorqueEnable did not answer within 5.0 s: asking again',
                               timeout=30)
    finally:
        asked_again.set()  # the late answer; also when the test fails, so the probe's thread ends
    control_servo.wait_for(r'torque enabled: pan', timeout=30)
    assert len(enable_requests) == 2
    control_servo.stop_cleanly(timeout=10)
    assert 'torque disabled: pan' in control_servo.output
    assert 'Traceback' not in control_servo.output


def goal_rate(goals, count):
    """Goals per second as control_servo sent them, from the send times of (sent ns, goal) goals.

    Timed over the first count + 1 goals sent from now on: one sent before a parameter change that has
    just been answered may still be on its way, and one the probe takes late is still timed when sent.
    """
    now = time.time_ns()
    wait_until(lambda: sum(sent > now for sent, _ in goals) > count, 20, f'{count + 1} goals')
    sent_times = [sent for sent, _ in goals if sent > now][:count + 1]
    return count / ((sent_times[-1] - sent_times[0]) / 1e9)


def test_control_servo_frequency_and_amplitude_change_at_runtime_and_bad_values_are_refused(ros):
    servo = start_servo(ros, 'pan')
    control_servo = ros.run('olive_servo', 'control_servo', '--ros-args', '-p', 'amplitude:=0.5')
    control_servo.wait_for(r'torque enabled: pan', timeout=30)
    goals = ros.probe.collect_with_info(Float32, '/olive/servo/pan/goal/position', 'source_timestamp',
                                         COLLECT_DEPTH)
    wait_for_messages(goals, 1, timeout=20, what='the first goal')  # timed from there, not from discovery
    # 200 goals: the sine's input goes 2 rad on, so at amplitude 1 at least one would be above 0.84.
    assert goal_rate(goals, 200) > 60  # 100 asked for; the machine may be busy
    assert max(abs(goal.data) for _, goal in goals) <= 0.5
    probe = ros.probe
    assert all(r.successful for r in probe.set_parameters('/control_servo', frequency=10.0, amplitude=1.5))
    assert 5 <= goal_rate(goals, 10) <= 13
    for name, value, reason in (('frequency', 0.5, 'out of range'), ('frequency', 1000.0, 'out of range'),
                                ('amplitude', 1.6, 'out of range'), ('amplitude', -0.1, 'out of range'),
                                ('frequency', 'fast', 'type'), ('frequency', 100, 'type')):
        [result] = probe.set_parameters('/control_servo', **{name: value})
        assert not result.successful, (name, value, result.reason)
        assert reason in result.reason, (name, value, result.reason)
    assert probe.get_parameters('/control_servo', 'frequency', 'amplitude') == [10.0, 1.5]
    control_servo.stop_cleanly(timeout=10)
    assert_clean_servo(servo)


@pytest.mark.parametrize(('executable', 'args', 'message'), [
    ('control_servo', ['-p', 'frequency:=0.0'], 'out of range'),
    ('control_servo', ['-p', 'amplitude:=big'], "'amplitude' to 'big' of type 'STRING', expecting type"),
    ('imu_control_robot', ['-p', 'pan_min:=1.0', '-p', 'pan_max:=0.5'],
     'pan_min (1.0) must be less than pan_max (0.5)'),
    ('imu_control_robot', ['-p', 'tilt_max:=4.0'], 'out of range'),
    ('imu_control_robot', ['-p', 'imu_topic:=my imu'], "imu_topic 'my imu' is not a valid topic name"),
])
def test_bad_startup_parameters_end_with_one_line_and_code_2(ros, executable, args, message):
    node = ros.run('olive_servo', executable, '--ros-args', *args)
    assert node.wait(30) == 2
    assert len(node.lines) == 1, node.output
    assert node.lines[0].startswith(f'{executable}: error: '), node.output
    assert message in node.output


def test_pid_testing_alternates_between_1_57_and_0_rad_every_3_s_with_the_torque_on(ros):
    servo = start_servo(ros, 'pan')
    goals = collect(ros, 'pan', 'goal/position')
    joints = collect(ros, 'pan', 'joint')
    pid_testing = ros.run('olive_servo', 'pid_testing')
    servo.wait_for(r'\]: torque enabled$', timeout=30)
    wait_for_messages(goals, 1, timeout=20, what='the first goal')
    first = time.monotonic()
    assert goals[0].data == pytest.approx(1.57)
    wait_until(lambda: joint_near(joints, 1.57), 10, 'the pan joint at 1.57 rad')
    wait_for_messages(goals, 2, timeout=10, what='the second goal')
    assert 2.0 < time.monotonic() - first < 4.5
    assert goals[1].data == 0.0
    wait_until(lambda: joint_near(joints, 0.0), 10, 'the pan joint back at 0 rad')
    stopped = time.monotonic()
    pid_testing.stop_cleanly(timeout=10)
    assert time.monotonic() - stopped < 2.0  # Ctrl-C does not wait for the 3 s timer
    assert 'Traceback' not in pid_testing.output
    servo.wait_for(r'\]: torque disabled$', timeout=10)
    assert_clean_servo(servo)


def start_head(ros, *robot_args):
    """imu_sim (commanded), imu_control_robot, then both servos: no goal may precede the torque."""
    ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=command')
    robot = ros.run('olive_servo', 'imu_control_robot', *robot_args)
    robot.wait_for(r'waiting for service /olive/servo/pan/setTorqueEnable', timeout=30)
    servos = {name: start_servo(ros, name) for name in ('pan', 'tilt')}
    robot.wait_for(r'torque enabled: pan, tilt', timeout=30)
    return robot, servos


def commander(ros):
    publisher = ros.probe.node.create_publisher(Quaternion, f'/{IMU_NODE}/true_orientation', 10)
    wait_until(lambda: publisher.get_subscription_count() > 0, 20, 'true_orientation subscriber')

    def turn(roll, pitch, yaw):
        x, y, z, w = quat.from_euler(roll, pitch, yaw)
        publisher.publish(Quaternion(x=x, y=y, z=z, w=w))
    return turn


def test_imu_control_robot_points_the_head_where_the_imu_points_within_the_bounds(ros):
    goals = {name: collect(ros, name, 'goal/position') for name in ('pan', 'tilt')}
    joints = {name: collect(ros, name, 'joint') for name in ('pan', 'tilt')}
    robot, servos = start_head(ros)
    turn = commander(ros)

    def goals_near(pan, tilt, tolerance=0.02):
        return (goals['pan'] and goals['tilt'] and abs(goals['pan'][-1].data - pan) < tolerance
                and abs(goals['tilt'][-1].data - tilt) < tolerance)

    def head_near(pan, tilt):
        return joint_near(joints['pan'], pan) and joint_near(joints['tilt'], tilt)

    # Turned left and nose down: pan turns left (positive), the camera looks down (positive tilt).
    turn(0.3, 0.4, 0.6)
    wait_until(lambda: goals_near(0.6, 0.4), 20, 'goals pan 0.6, tilt 0.4')
    wait_until(lambda: head_near(0.6, 0.4), 15, 'the head there')
    turn(0.0, -0.5, -0.6)
    wait_until(lambda: goals_near(-0.6, -0.5), 20, 'goals pan -0.6, tilt -0.5')
    wait_until(lambda: head_near(-0.6, -0.5), 15, 'the head there')
    # Beyond the bounds the goals stop at them.
    turn(0.0, 1.4, 2.5)
    wait_until(lambda: goals_near(BOUNDS['pan'][1], BOUNDS['tilt'][1], 1e-6), 20, 'goals at the upper bounds')
    turn(0.0, -1.45, -2.5)
    wait_until(lambda: goals_near(BOUNDS['pan'][0], BOUNDS['tilt'][0], 1e-6), 20, 'goals at the lower bounds')
    for name, (low, high) in BOUNDS.items():
        assert all(low - 1e-6 <= g.data <= high + 1e-6 for g in goals[name]), name
    robot.stop_cleanly(timeout=10)
    assert 'Traceback' not in robot.output
    for name, servo in servos.items():
        servo.wait_for(r'\]: torque disabled$', timeout=10)
        assert_clean_servo(servo)
        assert f'torque disabled: {name}' in robot.output


def test_imu_control_robot_bounds_change_at_runtime_and_bad_ones_are_refused(ros):
    goals = collect(ros, 'tilt', 'goal/position')
    robot, servos = start_head(ros)
    turn = commander(ros)
    probe = ros.probe
    assert all(r.successful for r in probe.set_parameters('/imu_control_robot', tilt_max=0.5))
    turn(0.0, 0.8, 0.0)
    wait_until(lambda: goals and goals[-1].data == pytest.approx(0.5), 20, 'tilt goal held at 0.5')
    for values, reason in (({'tilt_min': 0.6}, 'tilt_min (0.6) must be less than tilt_max (0.5)'),
                           ({'pan_max': -1.6}, 'pan_min (-1.5708) must be less than pan_max (-1.6)'),
                           ({'pan_max': 3.5}, 'out of range'), ({'tilt_min': 'low'}, 'type'),
                           ({'imu_topic': '/elsewhere'}, 'read-only')):
        [result] = probe.set_parameters('/imu_control_robot', **values)
        assert not result.successful, (values, result.reason)
        assert reason in result.reason, (values, result.reason)
    assert probe.get_parameters('/imu_control_robot', 'pan_min', 'pan_max', 'tilt_min', 'tilt_max') == [
        -1.5708, 1.5708, -1.3, 0.5]
    robot.stop_cleanly(timeout=10)
    for servo in servos.values():
        assert_clean_servo(servo)


def test_imu_control_robot_names_the_topic_it_waits_for_and_ignores_unusable_orientations(ros):
    goals = collect(ros, 'pan', 'goal/position')
    servos = {name: start_servo(ros, name) for name in ('pan', 'tilt')}
    robot = ros.run('olive_servo', 'imu_control_robot', '--ros-args', '-p', 'imu_topic:=/test_imu')
    robot.wait_for(r'waiting for IMU messages on /test_imu \(0 publisher\(s\) so far\)', timeout=30)
    imu = ros.probe.node.create_publisher(Imu, '/test_imu', 10)
    wait_until(lambda: imu.get_subscription_count() > 0, 20, 'imu_control_robot subscribing')
    bad = Imu()
    bad.orientation = Quaternion(x=0.0, y=0.0, z=0.0, w=0.0)
    for _ in range(50):
        imu.publish(bad)
        time.sleep(0.01)
    robot.wait_for(r'IMU message ignored: the orientation quaternion is zero, not a rotation')
    # Throttled to one line per 2 s: one for the 50 (two when a busy machine spread their handling
    # past 2 s), never one each.
    assert len([line for line in robot.lines if 'IMU message ignored' in line]) in (1, 2)
    assert goals == []
    good = Imu()
    x, y, z, w = quat.from_euler(0.0, 0.0, 0.3)
    good.orientation = Quaternion(x=x, y=y, z=z, w=w)
    imu.publish(good)
    wait_until(lambda: goals and goals[-1].data == pytest.approx(0.3), 10, 'pan goal 0.3')
    robot.wait_for(r'no usable IMU message on /test_imu for 0.5 s: the servos hold', timeout=10)
    robot.stop_cleanly(timeout=10)
    for servo in servos.values():
        assert_clean_servo(servo)


def test_the_scripted_imu_sweeps_both_servos_through_most_of_their_range(ros):
    """Issue 11 item 4: olive_sim's default IMU motion moves the whole head."""
    joints = {name: collect(ros, name, 'joint') for name in ('pan', 'tilt')}
    servos = {name: start_servo(ros, name) for name in ('pan', 'tilt')}
    ros.run('olive_sim', 'imu_sim')
    robot = ros.run('olive_servo', 'imu_control_robot')
    robot.wait_for(r'IMU data on .*: steering the pan and tilt servos', timeout=30)
    start = {name: len(messages) for name, messages in joints.items()}

    def swept() -> dict[str, float]:
        """Share of each servo's range its joint has covered since the robot took over."""
        spans = {}
        for name, (low, high) in BOUNDS.items():
            positions = [m.position[0] for m in joints[name][start[name]:]] or [0.0]
            spans[name] = (max(positions) - min(positions)) / (high - low)
        return spans

    deadline = time.monotonic() + 13.0  # a period of the yaw (12 s) and more than one of the pitch (10 s)
    while min(swept().values()) <= 0.75 and time.monotonic() < deadline:
        time.sleep(0.1)
    assert min(swept().values()) > 0.75, swept()
    robot.stop_cleanly(timeout=10)
    for servo in servos.values():
        assert 'torque enabled' in servo.output
        assert TORQUE_OFF_WARNING not in servo.output
