"""servo_sim over real DDS: the course's interface, torque safety, the PID exercise, bad input."""

import itertools
import math
import os
import signal
import statistics
import time

import pytest
from diagnostic_msgs.msg import DiagnosticStatus
from olive_sim.servo_model import step_metrics
from rclpy.qos import DurabilityPolicy, ReliabilityPolicy
from ros_harness import endpoints, list_parameter_names, wait_for_messages, wait_until
from sensor_msgs.msg import JointState, Temperature
from servo_helpers import COLLECT_DEPTH
from std_msgs.msg import Bool, Float32, String
from std_srvs.srv import Trigger

NODE = 'olive_servo_pan_dcm_srv'
PREFIX = '/olive/servo/pan/'
# The course's `ros2 topic list` for one servo (section 4.4), with the types the issue names.
PUBLISHED = {
    'joint': 'sensor_msgs/msg/JointState',
    'joint/diagnostics': 'diagnostic_msgs/msg/DiagnosticStatus',
    'status': 'diagnostic_msgs/msg/DiagnosticStatus',
    'switch': 'std_msgs/msg/Bool',
    'temperature': 'sensor_msgs/msg/Temperature',
}
SUBSCRIBED = {'goal/position': 'std_msgs/msg/Float32', 'led': 'std_msgs/msg/Bool'}
DEFAULTS = {
    'namespace': 'pan', 'control_mode': 'position', 'kp': 5.0, 'ki': 10.0, 'kd': 0.3,
    'physics_rate': 1000.0, 'pid_rate': 500.0, 'joint_rate': 100.0, 'button_pressed': False,
    'inertia': 0.02, 'stall_torque': 1.5, 'no_load_speed': 6.0, 'max_torque': 1.5,
    'viscous_friction': 0.01, 'coulomb_friction': 0.15, 'load_mass': 0.0, 'load_offset': 0.04,
    'min_position': -math.pi, 'max_position': math.pi, 'ambient_temperature': 25.0,
    'encoder_counts': 4096, 'use_sim_time': False, 'start_type_description_service': True,
    'address': '10.42.0.7', 'web_port': 8042,
}


def start_servo(ros, *args):
    servo = ros.run('olive_sim', 'servo_sim', *args)
    ros.probe.wait_for_node(NODE, timeout=20)
    return servo


def call(ros, service):
    return ros.probe.call(Trigger, PREFIX + service, Trigger.Request())


def goal(ros, value, topic='goal/position'):
    publisher = ros.probe.node.create_publisher(Float32, PREFIX + topic, 10)
    endpoints(ros.probe, PREFIX + topic, 'subscriptions')
    wait_until(lambda: publisher.get_subscription_count() > 0, 10, f'{topic} subscriber')
    publisher.publish(Float32(data=value))
    return publisher


def positions(joints):
    return [m.position[0] for m in joints]


def test_interface_matches_the_course(ros):
    start_servo(ros)
    probe = ros.probe
    for name, type_name in PUBLISHED.items():
        info = endpoints(probe, PREFIX + name)[0]
        assert (info.node_name, info.topic_type) == (NODE, type_name)
        assert info.qos_profile.reliability == ReliabilityPolicy.RELIABLE
        assert info.qos_profile.durability == DurabilityPolicy.VOLATILE
    for name, type_name in SUBSCRIBED.items():
        info = endpoints(probe, PREFIX + name, 'subscriptions')[0]
        assert (info.node_name, info.topic_type) == (NODE, type_name)
    topics = {t for t, _ in probe.node.get_topic_names_and_types() if t.startswith(PREFIX)}
    assert topics == {PREFIX + t for t in (*PUBLISHED, *SUBSCRIBED)}  # as the course lists them
    expected = {PREFIX + name: ['std_srvs/srv/Trigger'] for name in ('setTorqueEnable', 'setTorqueDisable')}
    wait_until(lambda: expected.items() <= dict(
        probe.node.get_service_names_and_types_by_node(NODE, '/')).items(), 15, 'the module services')
    names = list_parameter_names(probe, NODE)
    assert names == sorted(DEFAULTS)
    assert dict(zip(names, probe.get_parameters(NODE, *names), strict=True)) == pytest.approx(DEFAULTS)
    # Deep: with the default 10, a probe held back a moment under load dropped joints (a 100 Hz
    # servo measured at 84 Hz in a suite run).
    joints = probe.collect(JointState, PREFIX + 'joint', COLLECT_DEPTH)
    status = probe.collect(DiagnosticStatus, PREFIX + 'status')
    temperature = probe.collect(Temperature, PREFIX + 'temperature')
    switch = probe.collect(Bool, PREFIX + 'switch')
    wait_for_messages(status, 2)
    wait_for_messages(temperature, 1)
    wait_for_messages(switch, 1)
    # The module's schedule: a tick the busy machine delayed or skipped does not move the median.
    intervals = [stamp(later) - stamp(earlier) for earlier, later in itertools.pairwise(joints)]
    assert statistics.median(intervals) == pytest.approx(1 / 100.0, rel=0.05)
    assert joints[-1].name == ['pan_joint']
    assert len(joints[-1].effort) == 1
    values = {kv.key: kv.value for kv in status[-1].values}
    assert values['led'] == 'off'
    assert values['torque_enabled'] == 'false'
    led = probe.node.create_publisher(Bool, PREFIX + 'led', 10)
    wait_until(lambda: led.get_subscription_count() > 0, 10, 'led subscriber')
    led.publish(Bool(data=True))
    wait_until(lambda: any(kv.value == 'on' for kv in status[-1].values if kv.key == 'led'), 5, 'LED on')
    assert probe.set_parameters(NODE, control_mode='velocity')[0].successful
    endpoints(probe, PREFIX + 'goal/velocity', 'subscriptions')
    wait_until(lambda: not probe.node.get_subscriptions_info_by_topic(PREFIX + 'goal/position'), 10,
               'goal/position to go away in velocity mode')


def stamp(msg):
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def test_a_servo_held_up_still_stamps_its_joint_states_at_their_rate(ros):
    # As the IMU: a loaded machine delays the joint states, not their measurement, so a plot or a
    # rise time read from their stamps stays true (robot_view plots them at their stamps).
    servo = start_servo(ros)
    joints = ros.probe.collect(JointState, PREFIX + 'joint', COLLECT_DEPTH)
    wait_for_messages(joints, 20, timeout=20)
    # From the last few before the stop: a hold-up longer than SENSOR_CATCH_UP while the servo and
    # the subscription start is a real gap, and not this test's (0.213 s between the first two, once).
    first = len(joints) - 5
    os.kill(servo.pid, signal.SIGSTOP)
    time.sleep(0.08)
    os.kill(servo.pid, signal.SIGCONT)
    wait_for_messages(joints, first + 60, timeout=10)
    stamps = [stamp(m) for m in joints[first:first + 60]]
    gaps = [later - earlier for earlier, later in itertools.pairwise(stamps)]
    assert min(gaps) > 0.008, [round(g, 4) for g in gaps]
    assert max(gaps) < 0.012, [round(g, 4) for g in gaps]


def test_goals_ignored_with_torque_off_and_tracked_with_torque_on(ros):
    servo = start_servo(ros)
    joints = ros.probe.collect(JointState, PREFIX + 'joint')
    goal(ros, 1.0)
    servo.wait_for(r'goal/position: ignored, torque is disabled \(call /olive/servo/pan/setTorqueEnable')
    time.sleep(0.5)
    assert max(abs(p) for p in positions(joints)) < 0.01
    response = call(ros, 'setTorqueEnable')
    assert response.success
    assert response.message == 'torque enabled'
    goal(ros, 1.0)
    wait_until(lambda: joints and abs(joints[-1].position[0] - 1.0) < 0.01, 10, 'the joint at 1.0 rad')
    assert call(ros, 'setTorqueEnable').message == 'torque already enabled'
    assert call(ros, 'setTorqueDisable').message == 'torque disabled'


def settled(joints, messages=20, speed=0.01):
    """Whether the joint has been still (|velocity| < speed rad/s) for its last messages (0.2 s)."""
    return len(joints) >= messages and all(abs(m.velocity[0]) < speed for m in joints[-messages:])


def measure_step(ros, publisher, joints, target, seconds=3.0):
    """Publish a position goal once the joint is still, and measure the step response from the joint topic.

    Each step starts from rest: one started while the last one still rang (with I, a 45 % overshoot
    rings past 3 s) measured a different overshoot each time (0.37 rad once, against a bound of 0.35).
    """
    wait_until(lambda: settled(joints), 15, 'the joint at rest')
    start_index = len(joints)
    start = joints[-1].position[0]
    publisher.publish(Float32(data=target))
    wait_until(lambda: len(joints) > start_index and stamp(joints[-1]) - stamp(joints[start_index]) > seconds,
               seconds * 4, f'{seconds} s of joint states')
    window = joints[start_index:]
    t0 = stamp(window[0])
    return step_metrics([stamp(m) - t0 for m in window], positions(window), start, target)


def test_the_course_pid_exercise_over_dds(ros):
    # Section 4.4 with the appendix 5.3 script: the goal alternates between 0 and 1.57 every 3 s.
    start_servo(ros)
    joints = ros.probe.collect(JointState, PREFIX + 'joint')
    assert ros.probe.set_parameters(NODE, kp=1.0, ki=0.0, kd=0.0)[0].successful
    call(ros, 'setTorqueEnable')
    publisher = goal(ros, 0.0)
    wait_for_messages(joints, 10)
    # Each step is watched as long as its numbers take to show, not always the script's 3 s: without I
    # the joint stops within a second (friction holds the error); with I it takes longer to remove it.
    p_only = measure_step(ros, publisher, joints, 1.57, seconds=1.5)
    assert p_only.steady_state_error > 0.03
    ros.probe.set_parameters(NODE, kp=5.0)
    fast = measure_step(ros, publisher, joints, 0.0, seconds=1.5)
    assert fast.rise_time < p_only.rise_time
    assert fast.overshoot > p_only.overshoot + 0.05
    ros.probe.set_parameters(NODE, ki=10.0)
    with_i = measure_step(ros, publisher, joints, 1.57)
    assert with_i.steady_state_error < 0.01
    ros.probe.set_parameters(NODE, kd=1.0)
    with_d = measure_step(ros, publisher, joints, 0.0, seconds=2.0)
    assert with_d.overshoot < with_i.overshoot / 2


def test_velocity_and_pwm_modes(ros):
    servo = start_servo(ros, '--ros-args', '-p', 'control_mode:=velocity')
    joints = ros.probe.collect(JointState, PREFIX + 'joint')
    call(ros, 'setTorqueEnable')
    goal(ros, 2.0, 'goal/velocity')
    wait_until(lambda: joints and abs(joints[-1].velocity[0] - 2.0) < 0.15, 10, 'turning at 2 rad/s')
    goal(ros, 50.0, 'goal/velocity')
    servo.wait_for(r'goal/velocity 50\.000 rad/s is beyond the speed limit 6\.000: clamped')
    assert ros.probe.set_parameters(NODE, control_mode='pwm')[0].successful
    goal(ros, -0.5, 'pwm')
    wait_until(lambda: joints and joints[-1].velocity[0] < -1.0, 10, 'turning backwards on pwm')


def test_bad_input_is_refused_or_warned_and_never_moves_the_joint(ros):
    servo = start_servo(ros, '--ros-args', '-p', 'min_position:=-1.0', '-p', 'max_position:=1.0')
    probe = ros.probe
    joints = probe.collect(JointState, PREFIX + 'joint')
    call(ros, 'setTorqueEnable')
    publisher = goal(ros, math.nan)
    servo.wait_for(r'goal/position: ignored nan, a goal must be a finite number')
    publisher.publish(Float32(data=math.inf))
    servo.wait_for(r'ignored inf, a goal must be a finite number')
    time.sleep(0.3)
    assert max(abs(p) for p in positions(joints)) < 0.01
    publisher.publish(Float32(data=2.5))
    servo.wait_for(r'goal/position 2\.5000 rad is outside \[-1\.0000, 1\.0000\]: clamped to 1\.0000')
    wait_until(lambda: abs(joints[-1].position[0] - 1.0) < 0.01, 10, 'the joint at the clamp')
    refused = {
        'kp': -1.0, 'ki': -0.5, 'kd': -0.1,       # negative gains
        'control_mode': 'torque',                 # unknown mode
        'physics_rate': 2000.0,                   # read-only
    }
    for name, value in refused.items():
        result = probe.set_parameters(NODE, **{name: value})[0]
        assert not result.successful, name
        assert result.reason, name
    assert "unknown control_mode 'torque'" in probe.set_parameters(NODE, control_mode='torque')[0].reason
    assert not probe.set_parameters(NODE, kp='high')[0].successful      # wrong type
    assert not probe.set_parameters(NODE, kp=math.nan)[0].successful
    assert probe.get_parameters(NODE, 'kp', 'control_mode') == [5.0, 'position']
    probe.set_parameters(NODE, control_mode='pwm')
    pwm = goal(ros, 1.5, 'pwm')
    servo.wait_for(r'pwm 1\.5 ignored: the duty cycle must be within -1\.\.1')
    pwm.publish(Float32(data=math.nan))
    servo.wait_for(r'pwm: ignored nan')
    led = probe.node.create_publisher(String, PREFIX + 'led', 10)
    servo.wait_for(r'/olive/servo/pan/led is published as std_msgs/msg/String by /owl_test_probe: '
                   r'the LED expects std_msgs/msg/Bool', timeout=15)
    del led
    assert servo.running()
    assert 'Traceback' not in servo.output
    count = len(joints)
    wait_until(lambda: len(joints) > count + 10, 5, 'joint states still flowing')


@pytest.mark.parametrize(('args', 'message'), [
    (['-p', 'control_mode:=torque'], "unknown control_mode 'torque'"),
    (['-p', 'namespace:=1pan'], "namespace '1pan' is not valid"),
    (['-p', 'kp:=-2.0'], 'kp'),
    (['-p', 'min_position:=2.0', '-p', 'max_position:=1.0'], 'must be below max_position'),
])
def test_bad_startup_parameters_exit_with_one_clear_line(ros, args, message):
    servo = ros.run('olive_sim', 'servo_sim', '--ros-args', *args)
    assert servo.wait(20) == 2
    assert message in servo.output
    assert 'Traceback' not in servo.output
