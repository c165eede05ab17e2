"""Network hosts on one Linux machine: network namespaces joined by a bridge.

The simulated kit uses it to run each module as a host of its own at the course's address (the
bridge of section 4.4.1), and the tests use it for classroom laptops. Each host is a namespace with
its loopback up and one veth link to a bridge in a namespace of its own, so the machine's own
network is left alone unless a host is joined to it on purpose (join_this_machine). Needs root.
"""

from __future__ import annotations

import ipaddress
import os
import shutil
import subprocess
import uuid


class NetworkSetupError(RuntimeError):
    """A host or the bridge could not be made; the message is one line saying why."""


def ip(*args: str) -> None:
    """Run `ip ARGS`; NetworkSetupError with ip's own words when it fails."""
    result = subprocess.run(['ip', *args], capture_output=True, text=True, timeout=10, check=False)
    if result.returncode != 0:
        lines = result.stderr.strip().splitlines()
        reason = lines[-1] if lines else f'exit code {result.returncode}'
        raise NetworkSetupError(f"'ip {' '.join(args)}' failed: {reason}")


def setup_problem() -> str | None:
    """Why namespaces cannot be made here (one line), or None."""
    if os.geteuid() != 0:
        return 'network namespaces need root (run it with sudo)'
    if shutil.which('ip') is None:
        return "iproute2's 'ip' command is missing ('sudo apt-get install iproute2')"
    return None


def address_problem(address: str, subnet: str, taken: list[str]) -> str | None:
    """Why address cannot be a host's on subnet (one line), or None."""
    try:
        value = ipaddress.IPv4Address(address)
    except ValueError:
        return f"'{address}' is not an IPv4 address"
    network = ipaddress.IPv4Network(subnet)
    if value not in network or value in (network.network_address, network.broadcast_address):
        return f'{address} is not a host address of the subnet {subnet}'
    if address in taken:
        return f'{address} is already taken on {subnet}'
    return None


class Lan:
    """A bridge and the hosts on it; close() deletes everything it made."""

    def __init__(self, prefix: str = 'owl', subnet: str = '10.42.0.0/24') -> None:
        problem = setup_problem()
        if problem:
            raise NetworkSetupError(problem)
        self.tag = f'{prefix}-{uuid.uuid4().hex[:6]}'
        self.subnet = ipaddress.IPv4Network(subnet)
        self.switch = f'{self.tag}-sw'
        self.hosts: dict[str, str] = {}      # host name -> its namespace
        self.ports: dict[str, str] = {}      # host name -> its port on the bridge
        self.addresses: dict[str, str] = {}  # host name -> its address
        self.joined_link: str | None = None  # this machine's link to the bridge, if joined
        ip('netns', 'add', self.switch)
        try:
            ip('-n', self.switch, 'link', 'add', 'br0', 'type', 'bridge')
            ip('-n', self.switch, 'link', 'set', 'br0', 'up')
        except NetworkSetupError:
            self.close()
            raise

    def _check_address(self, address: str) -> None:
        problem = address_problem(address, str(self.subnet), list(self.addresses.values()))
        if problem:
            raise NetworkSetupError(problem)

    def _plug(self, name: str, address: str, namespace: str | None) -> str:
        """A veth from namespace (None: this machine) to the bridge, with address on its end."""
        port = f'p{len(self.ports)}'
        local = 'eth0' if namespace else f'{self.tag}'[:15]
        where = ['netns', namespace] if namespace else []
        ip('link', 'add', local, *where, 'type', 'veth', 'peer', 'name', port, 'netns', self.switch)
        self.ports[name] = port
        self.addresses[name] = address
        ip('-n', self.switch, 'link', 'set', port, 'master', 'br0')
        ip('-n', self.switch, 'link', 'set', port, 'up')
        on = ['-n', namespace] if namespace else []
        ip(*on, 'addr', 'add', f'{address}/{self.subnet.prefixlen}', 'dev', local)
        ip(*on, 'link', 'set', local, 'up')
        return local

    def add_host(self, name: str, address: str | None) -> str:
        """Add a host, loopback up and the address on its link to the bridge; returns its namespace.

        With address None the host has no link at all: a machine not on this LAN.
        """
        if address is not None:
            self._check_address(address)
        namespace = f'{self.tag}-{name}'
        ip('netns', 'add', namespace)
        self.hosts[name] = namespace
        ip('-n', namespace, 'link', 'set', 'lo', 'up')
        if address is not None:
            self._plug(name, address, namespace)
        return namespace

    def join_this_machine(self, address: str) -> str:
        """Plug this machine itself into the bridge with the address; returns its new interface's name.

        Like a student's PC on the kit's bridge.
        """
        self._check_address(address)
        self.joined_link = self._plug('this machine', address, None)
        return self.joined_link

    def set_link(self, name: str, up: bool) -> None:
        """Pull out or plug back in a host's cable (its port on the bridge)."""
        ip('-n', self.switch, 'link', 'set', self.ports[name], 'up' if up else 'down')

    def exec_argv(self, host: str, argv: list[str]) -> list[str]:
        """The argv that runs argv on a host."""
        return ['ip', 'netns', 'exec', self.hosts[host], *argv]

    def close(self) -> None:
        """Delete this machine's link, the hosts and the bridge; what fails or is gone already is skipped."""
        if self.joined_link is not None:
            subprocess.run(['ip', 'link', 'del', self.joined_link], capture_output=True, timeout=10,
                           check=False)
        for namespace in [*self.hosts.values(), self.switch]:
            subprocess.run(['ip', 'netns', 'del', namespace], capture_output=True, timeout=10, check=False)
