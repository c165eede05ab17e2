"""imu_sim over real DDS: the course's interface, physics of the readings, services, bad input."""

import itertools
import math
import os
import signal
import statistics
import time

import pytest
from geometry_msgs.msg import Quaternion
from owl_common import quaternion as quat
from rclpy.qos import ReliabilityPolicy
from ros_harness import endpoints, list_parameter_names, wait_for_messages, wait_until
from sensor_msgs.msg import Imu, MagneticField
from std_srvs.srv import Trigger

NAMESPACE = 'x1684267976913'  # the course's IMU
NODE = f'olive_imu_{NAMESPACE}_dcm_srv'
PREFIX = f'/olive/imu/{NAMESPACE}/'
PUBLISHED = {
    'imu': 'sensor_msgs/msg/Imu',
    'magnetometer': 'sensor_msgs/msg/MagneticField',
    'status': 'diagnostic_msgs/msg/DiagnosticStatus',
    'switch': 'std_msgs/msg/Bool',
    'temperature': 'sensor_msgs/msg/Temperature',
}
DEFAULTS = {
    'namespace': NAMESPACE, 'motion': 'scripted', 'motion_file': '', 'command_max_rate': 3.0,
    'gyro_noise': 0.002, 'gyro_bias': 0.005, 'accel_noise': 0.02, 'mag_noise': 0.2e-6,
    'orientation_noise': 0.002, 'seed': 0, 'imu_rate': 100.0, 'imu_frame_id': f'{NAMESPACE}_base_link',
    'imu_reliability': 'reliable', 'button_pressed': False, 'use_sim_time': False,
    'start_type_description_service': True, 'address': '10.42.0.7', 'web_port': 8042,
}


def stamp(msg):
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def orientation(msg):
    o = msg.orientation
    return (o.x, o.y, o.z, o.w)


def trigger(ros, name):
    return ros.probe.call(Trigger, PREFIX + name, Trigger.Request())


def test_interface_rate_and_gyro_integration_with_the_scripted_motion(ros):
    ros.run('olive_sim', 'imu_sim')
    probe = ros.probe
    probe.wait_for_node(NODE, timeout=20)
    for name, type_name in PUBLISHED.items():
        info = endpoints(probe, PREFIX + name)[0]
        assert (info.node_name, info.topic_type) == (NODE, type_name)
        assert info.qos_profile.reliability == ReliabilityPolicy.RELIABLE
    assert endpoints(probe, PREFIX + 'led', 'subscriptions')[0].topic_type == 'std_msgs/msg/Bool'
    topics = {t for t, _ in probe.node.get_topic_names_and_types() if t.startswith(PREFIX)}
    assert topics == {PREFIX + t for t in (*PUBLISHED, 'led')}  # the course's list
    expected = {PREFIX + name: ['std_srvs/srv/Trigger']
                for name in ('setBias', 'setZeroQuaternion', 'setZeroPose')}
    wait_until(lambda: expected.items() <= dict(
        probe.node.get_service_names_and_types_by_node(NODE, '/')).items(), 15, 'the module services')
    names = list_parameter_names(probe, NODE)
    assert names == sorted(DEFAULTS)
    assert dict(zip(names, probe.get_parameters(NODE, *names), strict=True)) == pytest.approx(DEFAULTS)

    imu = probe.collect(Imu, PREFIX + 'imu')
    wait_for_messages(imu, 300, timeout=20)
    window = imu[:301]
    # The module's schedule: a tick the busy machine delayed or skipped does not move the median.
    intervals = [stamp(later) - stamp(earlier) for earlier, later in itertools.pairwise(window)]
    assert statistics.median(intervals) == pytest.approx(1 / 100.0, rel=0.02)
    # Integrate the gyro over 1 s of the hand-held motion and compare with the orientation.
    second = [m for m in window if stamp(m) - stamp(window[0]) <= 1.0]
    integrated = orientation(second[0])
    for previous, msg in itertools.pairwise(second):
        w = msg.angular_velocity
        dt = stamp(msg) - stamp(previous)
        integrated = quat.multiply(integrated, quat.from_rotation_vector((w.x * dt, w.y * dt, w.z * dt)))
    assert quat.angle_between(orientation(second[0]), orientation(second[-1])) > 0.05
    assert quat.angle_between(integrated, orientation(second[-1])) < 0.03  # rad
    last = window[-1]
    assert last.orientation_covariance[0] > 0
    assert last.angular_velocity_covariance[4] > 0
    assert last.linear_acceleration_covariance[8] > 0
    response = trigger(ros, 'setBias')
    assert not response.success
    assert 'moving' in response.message


def test_a_module_held_up_still_stamps_its_samples_at_its_rate_and_says_when_it_cannot(ros):
    # A machine that holds the module up delays its messages, not its samples: their stamps keep
    # the 100 Hz spacing, as a real IMU's clock gives them, and the missed ones are sent late.
    module = ros.run('olive_sim', 'imu_sim')
    ros.probe.wait_for_node(NODE, timeout=20)
    # A deep queue on the test's side: a busy test process would drop the burst's oldest from a
    # depth-10 queue (6 lost in one clean-clone run), which says nothing of the module.
    imu = ros.probe.collect(Imu, PREFIX + 'imu', qos=100)
    wait_for_messages(imu, 20, timeout=20)
    # From the last few before the stop, as the servo's test: a hold-up by the machine itself while
    # the module and the subscription start is not this test's (0.331 s between the first two, once).
    first = len(imu) - 5
    os.kill(module.pid, signal.SIGSTOP)
    time.sleep(0.08)
    os.kill(module.pid, signal.SIGCONT)
    wait_for_messages(imu, first + 60, timeout=10)
    gaps = [stamp(later) - stamp(earlier) for earlier, later in itertools.pairwise(imu[first:first + 60])]
    # Every stamp on the module's 10 ms grid. The late ones come in a burst, and the module's depth-10
    # KEEP_LAST queue may drop the oldest of a burst rather than block (seen once: a 20 ms gap).
    shown = [round(g, 4) for g in gaps]
    ticks = [gap / 0.01 for gap in gaps]
    assert all(abs(tick - round(tick)) < 0.2 and round(tick) >= 1 for tick in ticks), shown
    assert sum(round(tick) - 1 for tick in ticks) <= 2, shown  # at most 2 lost
    # Held up longer than it makes up (SENSOR_CATCH_UP), the gap is real, and the module says why.
    os.kill(module.pid, signal.SIGSTOP)
    time.sleep(0.7)
    os.kill(module.pid, signal.SIGCONT)
    module.wait_for(r'imu: the machine held this module up \d+\.\d\d s, longer than the 0\.5 s it makes '
                    r'up; \d+ samples skipped')


def test_commanded_motion_gravity_heading_and_zeroing(ros):
    ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=command', '-p', 'seed:=4')
    probe = ros.probe
    probe.wait_for_node(NODE, timeout=20)
    imu = probe.collect(Imu, PREFIX + 'imu')
    mag = probe.collect(MagneticField, PREFIX + 'magnetometer')
    wait_for_messages(imu, 60)
    norms = [math.dist((0, 0, 0), (m.linear_acceleration.x, m.linear_acceleration.y,
                                   m.linear_acceleration.z)) for m in imu[-50:]]
    assert sum(norms) / len(norms) == pytest.approx(9.81, abs=0.05)
    response = trigger(ros, 'setBias')
    assert response.success, response.message

    def heading():
        f = mag[-1].magnetic_field
        return math.atan2(f.x, f.y)  # angle of magnetic north from the body's +y

    wait_for_messages(mag, 1)
    before = heading()
    command = probe.node.create_publisher(Quaternion, f'/{NODE}/true_orientation', 10)
    wait_until(lambda: command.get_subscription_count() > 0, 10, 'true_orientation subscriber')
    x, y, z, w = quat.from_euler(0.0, 0.0, 1.0)
    command.publish(Quaternion(x=x, y=y, z=z, w=w))
    wait_until(lambda: abs(quat.to_euler(orientation(imu[-1]))[2] - 1.0) < 0.02, 10, 'yaw 1.0')
    count = len(mag)
    wait_for_messages(mag, count + 20)
    turned = (heading() - before + math.pi) % (2 * math.pi) - math.pi
    assert turned == pytest.approx(1.0, abs=0.05)  # the heading follows yaw
    for service in ('setZeroQuaternion', 'setZeroPose'):
        assert trigger(ros, service).success
        count = len(imu)
        wait_for_messages(imu, count + 5)
        assert quat.angle_between(orientation(imu[-1]), quat.IDENTITY) < 0.02


def test_recorded_motion_file_plays(ros, tmp_path):
    path = tmp_path / 'turn.csv'
    path.write_text('0, 0, 0, 0\n1, 0, 0, 0.8\n2, 0, 0, 0\n')
    ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=file', '-p', f'motion_file:={path}')
    imu = ros.probe.collect(Imu, PREFIX + 'imu')
    wait_for_messages(imu, 250, timeout=20)
    yaws = [quat.to_euler(orientation(m))[2] for m in imu]
    assert max(yaws) == pytest.approx(0.8, abs=0.03)
    assert min(yaws) < 0.05


def test_bad_commands_are_warned_and_ignored(ros):
    imu_sim = ros.run('olive_sim', 'imu_sim', '--ros-args', '-p', 'motion:=command')
    probe = ros.probe
    probe.wait_for_node(NODE, timeout=20)
    command = probe.node.create_publisher(Quaternion, f'/{NODE}/true_orientation', 10)
    wait_until(lambda: command.get_subscription_count() > 0, 10, 'true_orientation subscriber')
    command.publish(Quaternion(x=math.nan, y=0.0, z=0.0, w=1.0))
    imu_sim.wait_for(r'true_orientation ignored: not a rotation')
    command.publish(Quaternion(x=0.0, y=0.0, z=0.0, w=0.0))
    imu_sim.wait_for(r'true_orientation ignored: not a rotation', count=2)
    for name, value in (('imu_rate', 50.0), ('seed', 3), ('gyro_noise', -1.0), ('motion', 'file')):
        result = probe.set_parameters(NODE, **{name: value})[0]
        assert not result.successful, name
        assert result.reason, name
    assert not probe.set_parameters(NODE, button_pressed='yes')[0].successful
    imu = probe.collect(Imu, PREFIX + 'imu')
    wait_for_messages(imu, 10)
    assert quat.angle_between(orientation(imu[-1]), quat.IDENTITY) < 0.02
    assert imu_sim.running()
    assert 'Traceback' not in imu_sim.output


@pytest.mark.parametrize(('args', 'message'), [
    (['-p', 'motion:=wiggle'], "unknown motion 'wiggle'"),
    (['-p', 'motion:=file', '-p', 'motion_file:=/nonexistent.csv'], "cannot read motion file"),
    (['-p', 'imu_reliability:=sometimes'], 'imu_reliability must be one of reliable, best_effort'),
    (['-p', 'namespace:=my-imu'], "namespace 'my-imu' is not valid"),
    (['-p', 'imu_rate:=0.0'], 'imu_rate'),
])
def test_bad_startup_parameters_exit_with_one_clear_line(ros, args, message):
    imu_sim = ros.run('olive_sim', 'imu_sim', '--ros-args', *args)
    assert imu_sim.wait(20) == 2
    assert message in imu_sim.output
    assert 'Traceback' not in imu_sim.output
