"""A module's Network Settings (IP, mask, Host PC / gateway) as its web page edits them.

A real module is a host at 10.42.0.N on its USB Ethernet link (section 4.4.1 of the course); its
web page is at http://10.42.0.N/. The simulated one answers at http://127.42.0.N:<port>/: Linux
routes all of 127.0.0.0/8 to the loopback interface with no set-up, so every module can have an
address of its own without root, and an IP change moves the page. Pure functions, no ROS.
"""

from __future__ import annotations

import ipaddress
import json
from dataclasses import asdict, dataclass
from typing import Any

FACTORY_ADDRESS = '10.42.0.7'  # every module's address out of the box (course, section 4.3.2)
DEFAULT_MASK = '255.255.255.0'
SHORTEST_PREFIX = 8   # a mask of 255.0.0.0 or longer
LONGEST_PREFIX = 30   # room for the module and the host PC
FIELDS = ('address', 'mask', 'gateway')
LABELS = {'address': 'Network IP', 'mask': 'Network Mask', 'gateway': 'Host PC / Gateway'}


@dataclass(frozen=True)
class NetworkSettings:
    """A module's address, mask and Host PC / gateway, as dotted IPv4 text."""

    address: str
    mask: str
    gateway: str

    def as_dict(self) -> dict[str, str]:
        """The settings as JSON-ready text fields: address, mask and gateway."""
        return asdict(self)

    @property
    def subnet(self) -> ipaddress.IPv4Network:
        """The network the address is on under the mask."""
        return ipaddress.IPv4Network(f'{self.address}/{self.mask}', strict=False)


def default_settings(address: str) -> NetworkSettings:
    """The settings of a module at address: a /24 whose first host is the host PC.

    That is 10.42.0.1 for the course's modules, the student's address on the kit's link.
    """
    ip = parse_address(address, 'address')
    subnet = ipaddress.IPv4Network(f'{ip}/{DEFAULT_MASK}', strict=False)
    return checked(NetworkSettings(str(ip), DEFAULT_MASK, str(subnet.network_address + 1)))


def parse_address(value: Any, field: str) -> ipaddress.IPv4Address:
    """A dotted IPv4 address as text; ValueError with one line otherwise."""
    label = LABELS.get(field, field)
    if not isinstance(value, str):
        raise ValueError(f'{label} must be a dotted IPv4 address such as 10.42.0.8, '
                         f'got {json.dumps(value)[:60]}')
    try:
        return ipaddress.IPv4Address(value)
    except ValueError:
        raise ValueError(f"{label} '{value[:60]}' is not an IPv4 address such as 10.42.0.8") from None


def parse_mask(value: Any) -> int:
    """The prefix length of a dotted network mask (255.255.255.0 -> 24); ValueError otherwise."""
    if not isinstance(value, str):
        raise ValueError(f'Network Mask must be dotted, such as 255.255.255.0, got {json.dumps(value)[:60]}')
    try:
        prefix = ipaddress.IPv4Network(f'0.0.0.0/{value}').prefixlen
    except ValueError:
        raise ValueError(f"Network Mask '{value[:60]}' is not a mask such as 255.255.255.0") from None
    if '.' not in value or not SHORTEST_PREFIX <= prefix <= LONGEST_PREFIX:
        raise ValueError(f"Network Mask '{value}' must be dotted, from 255.0.0.0 to 255.255.255.252")
    return prefix


def checked(settings: NetworkSettings) -> NetworkSettings:
    """Settings if a module can have them, else ValueError with one line naming the problem."""
    address = parse_address(settings.address, 'address')
    gateway = parse_address(settings.gateway, 'gateway')
    prefix = parse_mask(settings.mask)
    for field, ip in (('address', address), ('gateway', gateway)):
        if ip.is_loopback or ip.is_multicast or ip.is_unspecified or ip.is_reserved or ip.is_link_local:
            raise ValueError(f'{LABELS[field]} {ip} cannot be a host on the modules\' link '
                             '(loopback, multicast, link-local or reserved)')
    subnet = ipaddress.IPv4Network(f'{gateway}/{prefix}', strict=False)
    if address not in subnet:
        raise ValueError(f'Network IP {address} is outside the subnet {subnet} of the Host PC / '
                         f'Gateway {gateway}')
    if address in (subnet.network_address, subnet.broadcast_address):
        which = 'network' if address == subnet.network_address else 'broadcast'
        raise ValueError(f'Network IP {address} is the {which} address of {subnet}, not a host')
    if address == gateway:
        raise ValueError(f'Network IP {address} is the Host PC / Gateway\'s own address')
    return NetworkSettings(str(address), str(subnet.netmask), str(gateway))


def changed(current: NetworkSettings, request: dict[str, Any]) -> NetworkSettings:
    """Current with the fields the request gives (a subset of FIELDS), checked."""
    unknown = [key for key in request if key not in FIELDS]
    if unknown:
        raise ValueError(f"unknown field '{unknown[0][:40]}'; expected: {', '.join(FIELDS)}")
    return checked(NetworkSettings(**{**current.as_dict(), **request}))
