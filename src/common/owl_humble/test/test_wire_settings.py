"""Cyclone's settings from ROS 2's environment, and the twin's command line (no DDS)."""

import pytest
from owl_humble import twin, wire
from owl_humble.launcher import bridge_address


def test_the_discovery_range_and_static_peers_become_cyclone_settings():
    assert wire.ros_discovery_settings({}) == (0, 'SUBNET', [])
    env = {'ROS_DOMAIN_ID': '7', 'ROS_AUTOMATIC_DISCOVERY_RANGE': 'localhost',
           'ROS_STATIC_PEERS': '10.42.0.8; ;x'}
    assert wire.ros_discovery_settings(env) == (7, 'LOCALHOST', ['10.42.0.8', 'x'])
    assert wire.ros_discovery_settings({'ROS_AUTOMATIC_DISCOVERY_RANGE': 'SYSTEM_DEFAULT'})[1] == 'SUBNET'
    local = wire.cyclone_config('LOCALHOST', ['10.42.0.8'])
    assert '<NetworkInterface address="127.0.0.1"/>' in local
    assert '<Peer address="10.42.0.8"/>' in local
    assert '<AllowMulticast>false</AllowMulticast>' in local
    assert wire.cyclone_config('SUBNET', []) is None
    assert '<Peer address="10.42.0.9"/>' in wire.cyclone_config('SUBNET', ['10.42.0.9'])


def test_one_bridge_per_user_domain_and_range_and_none_where_it_cannot_help():
    local = {'ROS_DOMAIN_ID': '3', 'ROS_AUTOMATIC_DISCOVERY_RANGE': 'LOCALHOST'}
    assert bridge_address(local) is None  # private mode: no real module can be reached
    assert bridge_address(local, local_twin=True) is not None
    assert bridge_address({**local, 'ROS_STATIC_PEERS': '10.42.0.8'}) is not None
    subnet = bridge_address({'ROS_DOMAIN_ID': '3', 'ROS_AUTOMATIC_DISCOVERY_RANGE': 'SUBNET'})
    assert subnet is not None
    assert bridge_address(local, local_twin=True) != subnet
    assert bridge_address({'ROS_DOMAIN_ID': '3'}) != bridge_address({'ROS_DOMAIN_ID': '4'})
    assert bridge_address({'ROS_AUTOMATIC_DISCOVERY_RANGE': 'OFF'}) is None
    assert bridge_address({'RMW_IMPLEMENTATION': 'rmw_cyclonedds_cpp'}) is None


def test_opaque_types_are_made_once_per_name():
    first = wire.opaque_type('std_msgs::msg::dds_::Float32_')
    assert wire.opaque_type('std_msgs::msg::dds_::Float32_') is first
    assert wire.opaque_type('sensor_msgs::msg::dds_::Imu_') is not first
    assert twin.ros_type('sensor_msgs/msg/Imu') == 'sensor_msgs::msg::dds_::Imu_'


@pytest.mark.parametrize(('argv', 'problem'), [
    (['--module', 'camera'], "invalid choice: 'camera'"),
    (['--namespace', '1x'], "--namespace '1x' is not a ROS name"),
    (['--namespace', 'a/b'], 'is not a ROS name'),
    (['--rate', '0'], '--rate 0.0 is not between 0 and 1000'),
    (['--rate', 'nan'], 'is not between 0 and 1000'),
    (['--rate', 'fast'], "invalid float value: 'fast'"),
    (['--pitch', '2'], '--pitch 2.0 is not an angle'),
])
def test_bad_twin_arguments_get_one_line_and_exit_2(argv, problem, capsys):
    with pytest.raises(SystemExit) as exit_info:
        twin.parse_args(argv)
    assert exit_info.value.code == 2
    error = capsys.readouterr().err.splitlines()[-1]
    assert error.startswith('humble_twin: error: ')
    assert problem in error
