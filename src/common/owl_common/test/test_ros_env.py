"""The ROS environment's one reading: rcl's default domain 0 and Fast DDS's highest, the range, the peers."""

import pytest
from owl_common.ros_env import MAX_DOMAIN_ID, DomainIdError, discovery_range, domain_id, static_peers


@pytest.mark.parametrize(('environ', 'expected'), [
    ({}, 0),
    ({'ROS_DOMAIN_ID': ''}, 0),
    ({'ROS_DOMAIN_ID': '0'}, 0),
    ({'ROS_DOMAIN_ID': '42'}, 42),
    ({'ROS_DOMAIN_ID': str(MAX_DOMAIN_ID)}, MAX_DOMAIN_ID),
])
def test_an_unset_empty_or_usable_domain_is_read(environ, expected):
    assert domain_id(environ) == expected


@pytest.mark.parametrize('text', ['233', '300', '-1', 'abc', '4.5', ' 7', '²', '٣'])
def test_a_domain_no_node_can_use_is_one_sentence_with_the_range(text):
    with pytest.raises(DomainIdError) as refused:
        domain_id({'ROS_DOMAIN_ID': text})
    assert str(refused.value) == f"ROS_DOMAIN_ID is '{text}'; it must be a number from 0 to {MAX_DOMAIN_ID}"


def test_the_process_environment_is_read_by_default(monkeypatch):
    monkeypatch.setenv('ROS_DOMAIN_ID', '17')
    assert domain_id() == 17


@pytest.mark.parametrize(('value', 'expected'), [
    (None, 'SUBNET'), ('', 'SUBNET'), ('SYSTEM_DEFAULT', 'SUBNET'), ('localhost', 'LOCALHOST'),
    ('OFF', 'OFF'),
])
def test_the_discovery_range_is_in_capitals_with_subnet_by_default(value, expected):
    assert discovery_range({} if value is None else {'ROS_AUTOMATIC_DISCOVERY_RANGE': value}) == expected


def test_static_peers_are_the_non_blank_entries():
    assert static_peers({}) == []
    assert static_peers({'ROS_STATIC_PEERS': ' 10.42.0.8 ;; x; '}) == ['10.42.0.8', 'x']
