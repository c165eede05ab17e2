"""`owl network`: what this machine's ROS 2 reaches of the Olive modules, and what to fix.

Facts are gathered first (network mode, ROS domain, the machine's interfaces, which module addresses
answer, which Olive nodes DDS discovers); verdict() turns them into one line per check, each
problem with its fix. The course's set-up is the yardstick: modules at 10.42.0.x on USB Ethernet,
joined by the network bridge of section 4.4.1.
"""

from __future__ import annotations

import ipaddress
import json
import os
import socket
import subprocess
from dataclasses import dataclass, field

from olive_kit.description import KIT_SUBNET, OWL_KIT
from owl_humble.launcher import ensure_discovery_bridge

from owl_cli.network.kit import node_distribution
from owl_cli.network.wsl import HYPER_V_ALLOW, WslFacts, wsl_verdicts

FACTORY_ADDRESS = '10.42.0.7'  # every module's address out of the box (section 4.3.2)
# The addresses the course gives the modules, and what it calls them.
MODULE_ADDRESSES = {m.address: f'{m.module_type} {m.namespace}' for m in OWL_KIT}
DDS_PORTS = 'UDP 7400-7700'


@dataclass
class Interface:
    """One IPv4 address of a network interface of this machine, with its prefix length."""

    name: str
    address: str
    prefix: int
    multicast: bool = True  # the link's MULTICAST flag: DDS discovery needs it

    def __str__(self) -> str:
        return f'{self.name} {self.address}/{self.prefix}'


@dataclass
class NetworkFacts:
    """Everything `owl network` gathered before judging: this shell's ROS set-up, the network, the nodes."""

    discovery_range: str            # ROS_AUTOMATIC_DISCOVERY_RANGE of this shell
    domain_id: int
    interfaces: list[Interface]
    answering: dict[str, bool]      # module address -> it answered on the network
    olive_nodes: list[str]          # Olive module nodes DDS discovered in this shell's domain
    olive_nodes_in_domain_0: list[str] = field(default_factory=list)  # looked up when domain != 0
    distributions: dict[str, str] = field(default_factory=dict)  # node -> its ROS 2 distribution
    graph_profile: str | None = None  # the Fast DDS profile file in effect
    graph_protected: bool = True  # that profile keeps our graph messages from Humble modules
    wsl: WslFacts = field(default_factory=lambda: WslFacts(0))  # Windows' WSL, when this is it


@dataclass
class Verdict:
    """One line of `owl network`'s answer: ok, or a problem with its fix."""

    ok: bool
    text: str

    def __str__(self) -> str:
        return f"{'ok' if self.ok else 'problem'}: {self.text}"


def on_kit_subnet(interfaces: list[Interface]) -> list[Interface]:
    """Those of the interfaces whose address is on the modules' subnet (KIT_SUBNET, 10.42.0.0/24)."""
    subnet = ipaddress.IPv4Network(KIT_SUBNET)
    return [i for i in interfaces if ipaddress.IPv4Address(i.address) in subnet]


def verdict(facts: NetworkFacts) -> list[Verdict]:
    """One verdict per check, in the order a student would fix them."""
    verdicts = []
    if facts.discovery_range == 'LOCALHOST':
        verdicts.append(Verdict(False, 'network private: ROS 2 in this shell looks only at this machine, '
                                       'so no real module can be found; '
                                       'fix: export OWL_NETWORK=open; source env.sh'))
    else:
        verdicts.append(Verdict(True, f'network open (discovery range {facts.discovery_range}), '
                                      f'ROS domain {facts.domain_id}'))
    verdicts += [Verdict(ok, text) for ok, text in wsl_verdicts(facts.wsl)]
    local = on_kit_subnet(facts.interfaces)
    if local:
        verdicts.append(Verdict(True, f"{', '.join(map(str, local))} is on the modules' subnet {KIT_SUBNET}"))
    else:
        others = ', '.join(str(i) for i in facts.interfaces if not i.address.startswith('127.')) or 'none'
        verdicts.append(Verdict(False, f"no network interface on the modules' subnet {KIT_SUBNET} (this "
                                       f'machine has: {others}); fix: connect a module by USB, or put its '
                                       'link in the network bridge of section 4.4.1 with an address such as '
                                       '10.42.0.1/24'))
    for interface in local:
        if not interface.multicast:
            verdicts.append(Verdict(False, f'multicast is off on {interface.name}, and DDS discovery needs '
                                           f'it; fix: sudo ip link set {interface.name} multicast on'))
    answering = [a for a, up in facts.answering.items() if up and a in MODULE_ADDRESSES]
    if facts.answering.get(FACTORY_ADDRESS):
        verdicts.append(Verdict(False, f'a module answers at {FACTORY_ADDRESS}, the factory address; fix: '
                                       "set its course address in its web page's Network Settings "
                                       '(servos 10.42.0.8 and .9, camera .10, IMU .20; section 4.4.1)'))
    if answering:
        names = ', '.join(f'{MODULE_ADDRESSES[a]} at {a}' for a in answering)
        verdicts.append(Verdict(True, f'modules answer on the network: {names}'))
    elif local:
        verdicts.append(Verdict(False, f'no Olive module answers on {KIT_SUBNET}; fix: check the cables and '
                                       'the power module, and that every module link is in the bridge '
                                       '(section 4.4.1)'))
    if facts.olive_nodes:
        names = ', '.join(f'{n} ({facts.distributions[n]})' if n in facts.distributions else n
                          for n in sorted(facts.olive_nodes))
        verdicts.append(Verdict(True, f'ROS 2 discovers {len(facts.olive_nodes)} Olive module node(s) in '
                                      f'domain {facts.domain_id}: {names}'))
    elif facts.olive_nodes_in_domain_0:
        verdicts.append(Verdict(False, f'the modules\' nodes are in ROS domain 0, this shell is in domain '
                                       f'{facts.domain_id}; fix: export ROS_DOMAIN_ID=0'))
    elif answering and facts.discovery_range != 'LOCALHOST':
        fix = (f'allow it in the Hyper-V firewall (PowerShell as administrator): {HYPER_V_ALLOW}'
               if facts.wsl.networking == 'mirrored' else
               f"allow it on {local[0].name if local else 'the'} link, e.g. sudo ufw allow in proto udp to "
               'any port 7400:7700')
        verdicts.append(Verdict(False, f'modules answer on the network but ROS 2 discovers none of their '
                                       f'nodes in domain {facts.domain_id}: a firewall may block DDS '
                                       f'({DDS_PORTS}); fix: {fix}'))
    if facts.graph_protected:
        verdicts.append(Verdict(True, f'Humble modules are safe beside this shell: {facts.graph_profile} '
                                      'keeps our graph messages (ros_discovery_info) in a partition of their '
                                      'own, and the discovery bridge shows their nodes here'))
    else:
        verdicts.append(Verdict(False, f'the Fast DDS profile in effect ({facts.graph_profile or "none"}) '
                                       "does not keep our graph messages from Humble modules, which misread "
                                       "them (out of memory); fix: unset FASTRTPS_DEFAULT_PROFILES_FILE; "
                                       "source env.sh (or copy config/fastdds.xml's ros_discovery_info "
                                       'profiles into yours)'))
    return verdicts


# --- gathering the facts ------------------------------------------------------------------------

def interfaces() -> list[Interface]:
    """The machine's IPv4 addresses, from `ip -j -4 addr`."""
    result = subprocess.run(['ip', '-j', '-4', 'addr', 'show'], capture_output=True, text=True, timeout=10,
                            check=False)
    found = []
    for link in json.loads(result.stdout or '[]'):
        for info in link.get('addr_info', []):
            found.append(Interface(link['ifname'], info['local'], info['prefixlen'],
                                   'MULTICAST' in link.get('flags', ['MULTICAST'])))
    return found


def answers(address: str, timeout: float) -> bool:
    """Whether a host answers at address (TCP port 80) within timeout s.

    Any TCP answer counts, a refused connection too (its RST is an answer), so no web server and no
    root are needed.
    """
    try:
        with socket.create_connection((address, 80), timeout=timeout):
            return True
    except ConnectionRefusedError:
        return True
    except OSError:
        return False


def olive_nodes(domain_id: int, seconds: float) -> dict[str, str]:
    """The Olive module nodes (olive_*) DDS discovers in a domain within seconds, by name.

    Each maps to its ROS 2 distribution (kit.node_distribution).
    """
    import time

    import rclpy
    from rclpy.context import Context
    from rclpy.node import Node

    ensure_discovery_bridge({**os.environ, 'ROS_DOMAIN_ID': str(domain_id)})  # Humble modules' nodes
    context = Context()
    rclpy.init(context=context, domain_id=domain_id)
    try:
        node = Node('owl_network_check', context=context)
        deadline = time.monotonic() + seconds
        names: set[tuple[str, str]] = set()
        while time.monotonic() < deadline:
            names.update(n for n in node.get_node_names_and_namespaces() if n[0].startswith('olive_'))
            time.sleep(0.1)
        found = {name: node_distribution(node, name, namespace) for name, namespace in sorted(names)}
        node.destroy_node()
        return found
    finally:
        rclpy.try_shutdown(context=context)
