"""Network Settings of a module's page: what is accepted and what is refused in one line."""

import pytest
from olive_sim.network_settings import NetworkSettings, changed, checked, default_settings

KIT = NetworkSettings('10.42.0.8', '255.255.255.0', '10.42.0.1')


def test_default_settings_put_the_host_pc_first_on_a_slash_24():
    assert default_settings('10.42.0.20') == NetworkSettings('10.42.0.20', '255.255.255.0', '10.42.0.1')
    assert default_settings('192.168.7.2').gateway == '192.168.7.1'


def test_the_course_moves_the_lower_motor_from_the_factory_address():
    factory = default_settings('10.42.0.7')
    assert changed(factory, {'address': '10.42.0.8'}) == KIT


def test_mask_and_gateway_change_together_with_the_ip():
    moved = changed(KIT, {'address': '192.168.7.2', 'mask': '255.255.0.0', 'gateway': '192.168.7.100'})
    assert moved == NetworkSettings('192.168.7.2', '255.255.0.0', '192.168.7.100')


@pytest.mark.parametrize(('request_body', 'problem'), [
    ({'address': '10.42.1.9'}, 'outside the subnet 10.42.0.0/24'),
    ({'address': '10.42.0.256'}, 'is not an IPv4 address'),
    ({'address': '10.42.0'}, 'is not an IPv4 address'),
    ({'address': '010.42.0.8'}, 'is not an IPv4 address'),
    ({'address': 8}, 'must be a dotted IPv4 address'),
    ({'address': None}, 'must be a dotted IPv4 address'),
    ({'address': '10.42.0.0'}, 'network address'),
    ({'address': '10.42.0.255'}, 'broadcast address'),
    ({'address': '10.42.0.1'}, "Gateway's own address"),
    ({'address': '127.0.0.1', 'gateway': '127.0.0.2'}, 'cannot be a host'),
    ({'address': '224.0.0.5', 'gateway': '224.0.0.1'}, 'cannot be a host'),
    ({'mask': '255.0.255.0'}, 'is not a mask'),
    ({'mask': '24'}, 'must be dotted'),
    ({'mask': '255.255.255.255'}, 'must be dotted, from 255.0.0.0'),
    ({'gateway': '10.43.0.1'}, 'outside the subnet 10.43.0.0/24'),
    ({'adress': '10.42.0.9'}, "unknown field 'adress'"),
])
def test_bad_settings_are_refused_in_one_line(request_body, problem):
    with pytest.raises(ValueError, match=problem) as refused:
        changed(KIT, request_body)
    assert '\n' not in str(refused.value)


def test_checked_normalises_nothing_it_accepts():
    assert checked(KIT) == KIT
