"""ROS_DOMAIN_ID's one reading: rcl's default of 0, and Fast DDS's highest domain."""

import pytest
from owl_common.ros_domain import MAX_DOMAIN_ID, DomainIdError, domain_id


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
