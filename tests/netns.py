"""Test hosts on one machine: Linux network namespaces joined by a bridge, as a classroom's LAN or the
kit's USB-Ethernet bridge of section 4.4.1.

Each host is a namespace with loopback and one veth link to a bridge that lives in a namespace of its
own, so nothing of the machine's real network changes. Creating namespaces needs root; without it
(or without iproute2) the tests that use a Lan skip with one line.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import uuid
from pathlib import Path

import pytest
from owl_common.processes import RosProcess

ROOT = Path(__file__).resolve().parents[1]
SUBNET_PREFIX = 24


def ip(*args: str) -> None:
    result = subprocess.run(['ip', *args], capture_output=True, text=True, timeout=10, check=False)
    if result.returncode != 0:
        raise RuntimeError(f"'ip {' '.join(args)}' failed: {result.stderr.strip()}")


class Lan:
    """A bridge and hosts on it; close() deletes every namespace it made."""

    def __init__(self) -> None:
        if os.geteuid() != 0:
            pytest.skip('network namespaces need root, so this network test is skipped')
        if shutil.which('ip') is None:
            pytest.skip("iproute2's 'ip' is not installed, so this network test is skipped")
        self.tag = uuid.uuid4().hex[:6]
        self.switch = f'owl-{self.tag}-sw'
        self.hosts: dict[str, str] = {}  # host name -> its namespace
        self.links: dict[str, str] = {}  # host name -> its port on the bridge
        self.processes: list[RosProcess] = []
        try:
            ip('netns', 'add', self.switch)
        except RuntimeError as error:
            pytest.skip(f'cannot create a network namespace here ({error}), so this network test is skipped')
        ip('-n', self.switch, 'link', 'add', 'br0', 'type', 'bridge')
        ip('-n', self.switch, 'link', 'set', 'br0', 'up')

    def add_host(self, name: str, address: str) -> str:
        """A host with its loopback up and address/24 on its link to the bridge; returns its namespace."""
        namespace = f'owl-{self.tag}-{name}'
        port = f'p{len(self.hosts)}'
        ip('netns', 'add', namespace)
        self.hosts[name] = namespace
        self.links[name] = port
        ip('-n', namespace, 'link', 'set', 'lo', 'up')
        ip('link', 'add', 'eth0', 'netns', namespace, 'type', 'veth',
           'peer', 'name', port, 'netns', self.switch)
        ip('-n', self.switch, 'link', 'set', port, 'master', 'br0')
        ip('-n', self.switch, 'link', 'set', port, 'up')
        ip('-n', namespace, 'addr', 'add', f'{address}/{SUBNET_PREFIX}', 'dev', 'eth0')
        ip('-n', namespace, 'link', 'set', 'eth0', 'up')
        return namespace

    def set_link(self, name: str, up: bool) -> None:
        """Pull out or plug back in a host's cable (its port on the bridge)."""
        ip('-n', self.switch, 'link', 'set', self.links[name], 'up' if up else 'down')

    def run(self, host: str, command: str, env: dict[str, str], label: str | None = None) -> RosProcess:
        """A shell command on a host, in an `env.sh` shell of this checkout (env sets OWL_NETWORK and
        ROS_DOMAIN_ID as a user's shell would)."""
        process_env = {k: v for k, v in os.environ.items() if not k.startswith('ROS_AUTOMATIC_DISCOVERY')}
        process_env.update(env, PYTHONUNBUFFERED='1', RCUTILS_LOGGING_BUFFERED_STREAM='1')
        argv = ['ip', 'netns', 'exec', self.hosts[host], 'bash', '-c',
                f'source {ROOT}/env.sh && exec {command}']
        process = RosProcess(argv, process_env, label=label or f'{host}: {command}')
        self.processes.append(process)
        return process

    def close(self) -> None:
        for process in reversed(self.processes):
            if process.running():
                process.stop(timeout=3.0)
        for namespace in [*self.hosts.values(), self.switch]:
            subprocess.run(['ip', 'netns', 'del', namespace], capture_output=True, timeout=10, check=False)
