"""owl network --kit's pure parts: module names, distributions, verdicts."""

from owl_cli.network.kit import (
    HUMBLE,
    NEWER,
    ModuleReport,
    distribution,
    kit_verdicts,
    not_yet_seen,
    parse_module,
    torque_outcome,
)


def test_module_nodes_are_recognised_by_the_firmware_naming():
    assert parse_module('olive_servo_pan_dcm_srv') == ('servo', 'pan')
    assert parse_module('/olive_imu_x1684267976913_dcm_srv') == ('imu', 'x1684267976913')
    assert parse_module('olive_camera_id_01_dcm_srv') == ('camera', 'id_01')
    for other in ('turtlesim', 'olive_lamp_x_dcm_srv', 'olive_servo__dcm_srv', 'olive_servo_pan'):
        assert parse_module(other) is None


def test_no_type_hash_means_humble():
    assert distribution([0, 0]) == HUMBLE
    assert distribution([1, 1]) == NEWER
    assert distribution([0, 1]) == NEWER  # rmw's own endpoints aside, one hash is enough
    assert distribution([]) == 'unknown'


def test_the_kit_check_waits_for_a_node_found_earlier_until_its_endpoints_are_known_too():
    expected = {'olive_imu_humble_dcm_srv': HUMBLE, 'olive_servo_pan_dcm_srv': NEWER, 'olive_x': 'unknown'}
    # Names without endpoints (a run's owl network --kit read the Humble twins as "unknown").
    assert not_yet_seen(expected, {'olive_imu_humble_dcm_srv': 'unknown', 'olive_servo_pan_dcm_srv': NEWER}) \
        == ['olive_imu_humble_dcm_srv', 'olive_x']
    # A node the earlier look saw without endpoints needs only its name.
    assert not_yet_seen(expected, {'olive_imu_humble_dcm_srv': HUMBLE, 'olive_servo_pan_dcm_srv': NEWER,
                                   'olive_x': 'unknown'}) == []
    assert not_yet_seen({}, {}) == []


def test_a_module_passes_with_a_message_each_way_and_fails_naming_the_missing_way():
    good = ModuleReport('olive_imu_h_dcm_srv', 'imu', 'h', HUMBLE, 'one Imu on /olive/imu/h/imu',
                        'LED on on /olive/imu/h/led')
    mute = ModuleReport('olive_servo_pan_dcm_srv', 'servo', 'pan', NEWER, None, None)
    deaf = ModuleReport('olive_servo_tilt_dcm_srv', 'servo', 'tilt', NEWER, 'a JointState', None,
                        "setTorqueEnable answered in 3 ms ('torque already enabled'), torque left on", True)
    (ok, text), (bad, mute_text), (bad2, deaf_text) = kit_verdicts([good, mute, deaf])
    assert ok
    assert text.startswith('imu h (/olive_imu_h_dcm_srv, ROS 2 Humble): one Imu on')
    assert not bad
    assert 'nothing came from it and nothing sent to it was acknowledged and setTorqueEnable was not ' \
        'answered within 2 s' in mute_text
    assert not bad2
    assert 'nothing sent to it was acknowledged; fix:' in deaf_text
    assert good.topic('imu') == '/olive/imu/h/imu'
    [(none_ok, none_text)] = kit_verdicts([])
    assert not none_ok
    assert 'no Olive module node found' in none_text


def test_a_servo_passes_when_set_torque_enable_answers_and_its_torque_is_put_back():
    servo = ModuleReport('olive_servo_pan_dcm_srv', 'servo', 'pan', HUMBLE, 'one JointState', 'one goal')
    servo.torque_ok, servo.torque = torque_outcome((True, 'torque enabled', 0.004), (True, 'torque disabled'))
    [(ok, text)] = kit_verdicts([servo])
    assert ok
    assert text.endswith("one goal to it; setTorqueEnable answered in 4 ms ('torque enabled'), "
                         'torque switched off again')
    assert torque_outcome((True, 'Torque already enabled', 0.01), None) == (
        True, "setTorqueEnable answered in 10 ms ('Torque already enabled'), torque left on")
    # Switched on by us and not off again: a problem, said so.
    assert torque_outcome((True, 'torque enabled', 0.01), None) == (
        False, "setTorqueEnable answered in 10 ms ('torque enabled'), and setTorqueDisable did not answer "
               'within 2 s: its torque is ON')
    assert torque_outcome((False, 'driver fault', 0.01), None)[0] is False
    assert torque_outcome(None, None)[1].startswith('setTorqueEnable was not answered within 2 s')
