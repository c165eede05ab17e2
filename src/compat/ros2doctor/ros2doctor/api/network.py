"""Network: the machine's interfaces, and how far ROS 2 discovery reaches from here."""

from __future__ import annotations

import fcntl
import ipaddress
import os
import socket
import struct
from dataclasses import dataclass, field
from pathlib import Path

from owl_common.ros_env import DomainIdError, domain_id

from ros2doctor.api import DoctorCheck, DoctorReport, Report, Result
from ros2doctor.api.format import doctor_error, doctor_warn

SIOCGIFFLAGS = 0x8913
SIOCGIFADDR = 0x8915
SIOCGIFNETMASK = 0x891B
SIOCGIFBRDADDR = 0x8919
# The interface flags of <linux/if.h> that the report names.
FLAG_NAMES = {0x1: 'UP', 0x2: 'BROADCAST', 0x8: 'LOOPBACK', 0x10: 'POINTOPOINT', 0x40: 'RUNNING',
              0x100: 'PROMISC', 0x1000: 'MULTICAST'}
LOOPBACK, MULTICAST = 0x8, 0x1000
RANGES = ('SUBNET', 'LOCALHOST', 'OFF', 'SYSTEM_DEFAULT')


@dataclass
class Interface:
    """What the report shows of one network interface."""

    name: str
    flags: int = 0
    inet: str | None = None
    netmask: str | None = None
    broadcast: str | None = None
    inet6: list[str] = field(default_factory=list)
    ether: str | None = None
    mtu: int | None = None

    def flag_text(self) -> str:
        """e.g. '73<UP,LOOPBACK,RUNNING>'."""
        names = [name for bit, name in FLAG_NAMES.items() if self.flags & bit]
        return f"{self.flags}<{','.join(names)}>"


def _ioctl_address(sock: socket.socket, name: str, request: int) -> str | None:
    try:
        answer = fcntl.ioctl(sock.fileno(), request, struct.pack('256s', name.encode()[:15]))
    except OSError:
        return None
    return socket.inet_ntoa(answer[20:24])


def interfaces() -> list[Interface]:
    """The machine's network interfaces, read from the kernel (Linux)."""
    found = []
    ipv6: dict[str, list[str]] = {}
    inet6_file = Path('/proc/net/if_inet6')
    if inet6_file.exists():
        for line in inet6_file.read_text().splitlines():
            parts = line.split()
            if len(parts) >= 6:
                ipv6.setdefault(parts[5], []).append(str(ipaddress.IPv6Address(int(parts[0], 16))))
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
        for _, name in socket.if_nameindex():
            interface = Interface(name, inet6=ipv6.get(name, []))
            try:
                answer = fcntl.ioctl(sock.fileno(), SIOCGIFFLAGS, struct.pack('256s', name.encode()[:15]))
                interface.flags = struct.unpack('H', answer[16:18])[0]
            except OSError:
                pass
            interface.inet = _ioctl_address(sock, name, SIOCGIFADDR)
            interface.netmask = _ioctl_address(sock, name, SIOCGIFNETMASK)
            if interface.flags & 0x2:
                interface.broadcast = _ioctl_address(sock, name, SIOCGIFBRDADDR)
            sys_dir = Path('/sys/class/net') / name
            try:
                interface.mtu = int((sys_dir / 'mtu').read_text())
                mac = (sys_dir / 'address').read_text().strip()
                interface.ether = None if mac in ('', '00:00:00:00:00:00') else mac
            except (OSError, ValueError):
                pass
            found.append(interface)
    return found


def domain_id_problem() -> str | None:
    """Why ROS_DOMAIN_ID is one no node can use (Fast DDS ends the process on it), or None when it is fine."""
    try:
        domain_id()
    except DomainIdError as error:
        return str(error)
    return None


def discovery_settings() -> dict[str, str]:
    """The environment variables that decide how far discovery reaches, as set (or their defaults)."""
    return {
        'discovery range': os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE') or 'SYSTEM_DEFAULT (SUBNET)',
        'static peers': os.environ.get('ROS_STATIC_PEERS') or 'none',
        'domain id': os.environ.get('ROS_DOMAIN_ID') or '0 (default)',
    }


class NetworkCheck(DoctorCheck):
    """Interfaces to talk on, and a discovery range that can find other nodes."""

    def category(self) -> str:
        """'network'."""
        return 'network'

    def check(self) -> Result:
        """Loopback, a non-loopback interface and multicast; a valid, non-OFF discovery range."""
        result = Result()
        found = interfaces()
        if not any(i.flags & LOOPBACK for i in found):
            doctor_error('No loopback IP address is found.')
            result.add_error()
        if not any(not i.flags & LOOPBACK for i in found):
            doctor_warn('Only loopback IP address is found.')
            result.add_warning()
        if not any(i.flags & MULTICAST for i in found):
            doctor_warn('No multicast IP address is found.')
            result.add_warning()
        reach = os.environ.get('ROS_AUTOMATIC_DISCOVERY_RANGE', '')
        if reach and reach not in RANGES:
            doctor_error(f"ROS_AUTOMATIC_DISCOVERY_RANGE is '{reach}'; it must be one of "
                         f"{', '.join(RANGES)}.")
            result.add_error()
        elif reach == 'OFF' and not os.environ.get('ROS_STATIC_PEERS'):
            doctor_warn('ROS_AUTOMATIC_DISCOVERY_RANGE is OFF and ROS_STATIC_PEERS is empty: this machine '
                        'finds no other nodes, not even its own.')
            result.add_warning()
        if os.environ.get('ROS_LOCALHOST_ONLY'):
            doctor_warn('ROS_LOCALHOST_ONLY is deprecated since Jazzy; use ROS_AUTOMATIC_DISCOVERY_RANGE='
                        'LOCALHOST instead.')
            result.add_warning()
        if (problem := domain_id_problem()) is not None:
            doctor_error(f'{problem}.')
            result.add_error()
        return result


class NetworkReport(DoctorReport):
    """NETWORK CONFIGURATION: each interface, then the discovery settings."""

    def category(self) -> str:
        """'network'."""
        return 'network'

    def report(self) -> Report:
        """inet, inet6, ether, netmask, device, flags, mtu, broadcast per interface (those it has)."""
        report = Report('NETWORK CONFIGURATION')
        for interface in interfaces():
            for key, value in (('inet', interface.inet), ('inet6', interface.inet6),
                               ('ether', interface.ether), ('netmask', interface.netmask),
                               ('device', interface.name),
                               ('flags', interface.flag_text()), ('mtu', interface.mtu),
                               ('broadcast', interface.broadcast)):
                if value:
                    report.add_to_report(key, value)
        for key, value in discovery_settings().items():
            report.add_to_report(key, value)
        return report
