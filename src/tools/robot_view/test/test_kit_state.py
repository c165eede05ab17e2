"""The robot view's commands and joint lookup, without a node."""

import pytest
from olive_kit.description import CAMERA_TOPIC, IMU_TOPIC, goal_topic, joint_topic
from owl_web.codec import ApiError
from robot_view.kit_state import (
    LEVEL,
    STARTUP_GRACE,
    TRUE_ORIENTATION_TOPIC,
    first_presence_due,
    goal_outcome,
    hold_imu_orientation,
    joint_position,
    kit_presence,
    level_orientation,
    servo_unavailable,
    silences,
)
from robot_view.main import parse_arguments


def test_hold_imu_takes_one_unit_quaternion():
    assert hold_imu_orientation({'orientation': {'x': 0, 'y': 0, 'z': 0.6, 'w': 0.8}}) == \
        pytest.approx((0, 0, 0.6, 0.8))
    for arguments, error in [
            ({}, "missing key 'orientation'"),
            ({'orientation': {'x': 0, 'y': 0, 'z': 0, 'w': 1}, 'speed': 1},
             "unknown key 'speed'; expected: orientation"),
            ({'orientation': {'x': float('nan'), 'y': 0, 'z': 0, 'w': 1}},
             'the orientation: "x" must be finite, got nan'),
            ({'orientation': {'x': 0, 'y': 0, 'z': 0, 'w': 3}},
             'the orientation must be a unit quaternion (norm 1), got norm 3')]:
        with pytest.raises(ApiError) as refused:
            hold_imu_orientation(arguments)
        assert refused.value.message == error


def test_level_takes_nothing():
    assert level_orientation({}) == LEVEL
    with pytest.raises(ApiError, match="unknown key 'now'"):
        level_orientation({'now': True})


def test_joint_position_by_name():
    assert joint_position(['pan_joint'], [0.5], 'pan_joint') == 0.5
    assert joint_position(['tilt_joint'], [0.5], 'pan_joint') is None
    assert joint_position([], [], 'pan_joint') is None


def test_port_argument(capsys):
    assert parse_arguments(['--port', '0']).port == 0
    for bad in ('http', '70000', '-1'):
        with pytest.raises(SystemExit) as stopped:
            parse_arguments(['--port', bad])
        assert stopped.value.code == 2
    assert "is not a port number (0..65535)" in capsys.readouterr().err


def test_which_modules_run_and_what_steers_them_comes_from_the_graph():
    nothing = kit_presence({}, {})
    assert nothing == {'modules': {'pan': False, 'tilt': False, 'imu': False, 'camera': False},
                       'imu_steerable': False, 'steered': {'pan': [], 'tilt': []}}
    # the kit of robot_view.launch.py: an IMU that takes the page's orientation; robot_view's own
    # goal publishers steer nothing else
    kit = kit_presence({joint_topic('pan'): 1, joint_topic('tilt'): 1, IMU_TOPIC: 1, CAMERA_TOPIC: 1,
                        goal_topic('pan'): 1, goal_topic('tilt'): 1}, {TRUE_ORIENTATION_TOPIC: 1}, {})
    assert kit['modules'] == {'pan': True, 'tilt': True, 'imu': True, 'camera': True}
    assert kit['imu_steerable'] is True
    assert kit['steered'] == {'pan': [], 'tilt': []}
    # imu_control_robot publishes both servos' goals, and a script the pan's, twice (two publishers)
    steered = kit_presence({}, {}, {'pan': ['/imu_control_robot', '/my_script', '/imu_control_robot'],
                                    'tilt': ['/imu_control_robot']})
    assert steered['steered'] == {'pan': ['/imu_control_robot', '/my_script'], 'tilt': ['/imu_control_robot']}


def test_a_module_is_silent_from_a_second_after_its_last_message_in_whole_seconds():
    heard = {'imu': 100.0, 'pan': 99.5, 'tilt': 96.1}
    assert silences(heard, 100.2) == {'tilt': 4}
    assert silences(heard, 100.5) == {'pan': 1, 'tilt': 4}
    assert silences(heard, 101.0) == {'imu': 1, 'pan': 1, 'tilt': 4}
    assert silences({}, 100.0) == {}  # never heard: the graph says whether it runs


def test_a_servo_that_sends_nothing_gets_no_command_and_the_refusal_says_why():
    assert servo_unavailable('pan', None, heard=True) is None
    never = servo_unavailable('pan', None, heard=False)
    assert never is not None
    assert never.startswith('the pan servo has sent no joint state: is it running?')
    assert 'ros2 launch olive_sim owl_kit.launch.py' in never
    assert servo_unavailable('tilt', 4, heard=True) == 'no data from the tilt servo for 4 s: has it stopped?'


def test_a_module_still_starting_is_not_said_to_be_missing_in_the_first_seconds():
    starting = kit_presence({joint_topic('tilt'): 1, IMU_TOPIC: 1, CAMERA_TOPIC: 1}, {})
    everything = kit_presence({joint_topic('pan'): 1, joint_topic('tilt'): 1, IMU_TOPIC: 1, CAMERA_TOPIC: 1},
                              {})
    assert first_presence_due(everything, 1.0)
    assert not first_presence_due(starting, 1.0)
    assert not first_presence_due(kit_presence({}, {}), STARTUP_GRACE - 0.1)
    assert first_presence_due(starting, STARTUP_GRACE)
    assert first_presence_due(kit_presence({}, {}), STARTUP_GRACE + 5)


def test_a_goal_to_a_servo_whose_torque_is_off_is_ignored():
    ignored = goal_outcome('pan', False)
    assert ignored['outcome'] == 'ignored'
    assert "the pan servo's torque is off, so it ignores goals" in ignored['reason']
    assert goal_outcome('pan', True) == {'outcome': 'sent'}
    assert goal_outcome('tilt', None) == {'outcome': 'sent'}  # not known: the joint will tell


def test_a_goal_another_node_also_publishes_is_said_to_be_overridden_by_it():
    one = goal_outcome('pan', True, ['/imu_control_robot'])
    assert one['outcome'] == 'overridden'
    assert one['by'] == ['/imu_control_robot']
    assert one['reason'].startswith("/imu_control_robot also publishes the pan servo's goals, and its next "
                                    'goal replaces this one: stop it')
    two = goal_outcome('tilt', None, ['/a', '/b'])
    assert two['reason'].startswith("/a and /b also publish the tilt servo's goals, and their next goal")
    assert goal_outcome('pan', False, ['/imu_control_robot'])['outcome'] == 'ignored'  # torque off first
    assert goal_outcome('pan', True, []) == {'outcome': 'sent'}
