"""The kit's description: names, addresses and topics as the course and the modules give them."""

import ipaddress

import pytest
from olive_kit.description import (
    CAMERA_NAMESPACE,
    GAIN_LIMITS,
    IMU_NAMESPACE,
    OWL_KIT,
    SERVO_RANGES,
    address_table,
    node_name,
    page_host,
    topic_table,
)


def test_the_page_answers_at_127_and_the_last_three_octets():
    assert page_host('10.42.0.8') == '127.42.0.8'
    assert page_host('192.168.7.2') == '127.168.7.2'


@pytest.mark.parametrize('address', ['10.42.0', '10.42.0.256', 'module', ''])
def test_an_address_that_is_not_ipv4_is_refused(address):
    with pytest.raises(ipaddress.AddressValueError):  # a ValueError
        page_host(address)


def test_the_kit_is_the_courses_four_modules_at_their_addresses():
    assert [(m.module_type, m.namespace, m.address) for m in OWL_KIT] == [
        ('imu', IMU_NAMESPACE, '10.42.0.20'), ('servo', 'pan', '10.42.0.8'),
        ('servo', 'tilt', '10.42.0.9'), ('camera', 'eye', '10.42.0.10')]
    assert OWL_KIT[1].node == node_name('servo', 'pan') == 'olive_servo_pan_dcm_srv'
    assert OWL_KIT[1].page_url() == 'http://127.42.0.8:8042/'


def test_a_servos_topics_are_the_modules_with_their_types():
    topics = OWL_KIT[1].topics()
    assert topics['/olive/servo/pan/goal/position'] == 'std_msgs/msg/Float32'
    assert topics['/olive/servo/pan/joint'] == 'sensor_msgs/msg/JointState'
    assert topics['/olive/servo/pan/led'] == 'std_msgs/msg/Bool'


def test_the_tables_name_every_module():
    addresses, topics = address_table(), topic_table()
    for module in OWL_KIT:
        assert module.address in addresses
        assert module.page_url() in addresses
        assert module.node in topics


def test_gain_limits_are_the_pid_terms():
    assert set(GAIN_LIMITS) == {'kp', 'ki', 'kd'}
    assert all(v > 0 for v in GAIN_LIMITS.values())


def test_the_servos_ranges_and_the_cameras_namespace_are_the_kits():
    assert SERVO_RANGES == {'pan': (-1.5708, 1.5708), 'tilt': (-1.3, 0.9)}
    assert OWL_KIT[3].topics()[f'/olive/camera/{CAMERA_NAMESPACE}/image/compressed'] == (
        'sensor_msgs/msg/CompressedImage')
