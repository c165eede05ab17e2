"""owl network on Windows' WSL: WSL told from /proc/version and the environment, and each mode's verdict."""

import pytest
from owl_cli.network.checks import Interface, NetworkFacts, verdict
from owl_cli.network.wsl import HYPER_V_ALLOW, WslFacts, wsl_facts, wsl_verdicts

# /proc/version as each kind of machine writes it
WSL2 = ('Linux version 5.15.167.4-microsoft-standard-WSL2 (root@f9c826d3017f) (gcc (GCC) 11.2.0, GNU ld '
        '(GNU Binutils) 2.37) #1 SMP Tue Nov 5 00:21:55 UTC 2024')
WSL1 = ('Linux version 4.4.0-22621-Microsoft (Microsoft@Microsoft.com) (gcc version 5.4.0 (GCC) ) '
        '#3527-Microsoft')
UBUNTU = 'Linux version 6.8.0-49-generic (buildd@lcy02-amd64-103) (x86_64-linux-gnu-gcc-13 (Ubuntu 13.2.0)'
NAT_INTERFACES = [('lo', '127.0.0.1'), ('eth0', '172.23.112.5')]
MIRRORED_INTERFACES = [('lo', '127.0.0.1'), ('loopback0', '169.254.73.152'), ('eth0', '192.168.1.23'),
                       ('eth1', '10.42.0.1')]


def test_wsl_is_told_from_proc_version_or_the_environment():
    assert wsl_facts(UBUNTU, {}, '', NAT_INTERFACES) == WslFacts(0)
    assert wsl_facts(WSL2, {'WSL_DISTRO_NAME': 'Ubuntu-24.04'}, 'nat\n', NAT_INTERFACES) == \
        WslFacts(2, 'Ubuntu-24.04', 'nat', 'wslinfo')
    assert wsl_facts(WSL1, {}, '', []).version == 1
    # a custom kernel that hides its origin: WSL's own variable still says it
    assert wsl_facts(UBUNTU, {'WSL_DISTRO_NAME': 'Ubuntu-22.04'}, '', MIRRORED_INTERFACES) == \
        WslFacts(2, 'Ubuntu-22.04', 'mirrored', 'the interfaces')
    assert wsl_facts(WSL2, {}, '', NAT_INTERFACES).networking == 'nat'  # no wslinfo: a guess, said so
    assert wsl_facts(WSL2, {}, '', [('lo', '127.0.0.1'), ('eth0', '192.168.5.2')]).networking == ''


def test_each_networking_mode_gets_one_line_saying_what_to_change():
    assert wsl_verdicts(WslFacts(0)) == []
    [(ok, text)] = wsl_verdicts(WslFacts(2, 'Ubuntu-24.04', 'nat', 'wslinfo'))
    assert not ok
    assert text.startswith("WSL 2 with nat networking (from wslinfo): the Olive modules on the laptop's USB "
                           "Ethernet and DDS discovery's multicast do not reach it; fix: put "
                           r'networkingMode=mirrored under [wsl2] in %UserProfile%\.wslconfig')
    [(ok, text)] = wsl_verdicts(WslFacts(2, 'Ubuntu-24.04', 'mirrored', 'wslinfo'))
    assert ok
    assert 'front door' in text
    [(ok, text)] = wsl_verdicts(WslFacts(1, 'Ubuntu'))
    assert (ok, text) == (False, 'this is WSL 1, which has no Linux network of its own for ROS 2; fix: in '
                                 'PowerShell run wsl --set-version Ubuntu 2')
    [(ok, text)] = wsl_verdicts(WslFacts(2, 'Ubuntu-24.04', ''))
    assert not ok
    assert text.startswith('WSL 2 with an unknown networking: the kit needs mirrored networking; fix: ')


def facts(**changes):
    values = dict(discovery_range='SUBNET', domain_id=0, interfaces=[Interface('eth1', '10.42.0.1', 24)],
                  answering={'10.42.0.8': True}, olive_nodes=[])
    values.update(changes)
    return NetworkFacts(**values)


def test_owl_network_puts_the_wsl_line_first_and_the_hyper_v_firewall_in_the_fix():
    lines = [str(v) for v in verdict(facts(wsl=WslFacts(2, 'Ubuntu-24.04', 'mirrored', 'wslinfo')))]
    assert lines[1].startswith('ok: WSL 2 with mirrored networking')
    firewall = next(line for line in lines if 'a firewall may block DDS' in line)
    assert firewall.endswith(f'fix: allow it in the Hyper-V firewall (PowerShell as administrator): '
                             f'{HYPER_V_ALLOW}')
    lines = [str(v) for v in verdict(facts())]  # not WSL: the Linux firewall's fix
    assert lines[1].startswith('ok: eth1 10.42.0.1/24')
    assert 'sudo ufw allow in proto udp' in next(line for line in lines if 'firewall' in line)


def test_multicast_off_on_the_modules_link_is_a_problem_with_its_fix():
    off = facts(interfaces=[Interface('eth1', '10.42.0.1', 24, multicast=False)], olive_nodes=['olive_x'])
    assert [v.text for v in verdict(off) if not v.ok] == [
        'multicast is off on eth1, and DDS discovery needs it; fix: sudo ip link set eth1 multicast on']


@pytest.mark.parametrize('kernel', [WSL2, WSL1, UBUNTU])
def test_proc_version_alone_never_raises(kernel):
    assert wsl_facts(kernel, {}, '', []).version in (0, 1, 2)
