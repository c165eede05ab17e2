"""Talk to the daemon of this ROS domain: is it running, start it, stop it, ask it."""

import os
import socket
import subprocess
import sys
import time
import xmlrpc.client
from collections.abc import Callable
from typing import Any

from ros2cli.daemon import RPC_PATH, daemon_port, domain_id

READY_TIMEOUT = 10.0


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host: Any) -> Any:
        connection = super().make_connection(host)
        connection.timeout = self._timeout
        return connection


def _proxy(timeout: float) -> xmlrpc.client.ServerProxy:
    return xmlrpc.client.ServerProxy(
        f'http://127.0.0.1:{daemon_port()}{RPC_PATH}', transport=_TimeoutTransport(timeout),
        allow_none=True)


def _port_open() -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.settimeout(0.2)
        return probe.connect_ex(('127.0.0.1', daemon_port())) == 0


def is_daemon_running(timeout: float = 5.0) -> bool:
    """True when this domain's daemon answers (a starting daemon is waited for)."""
    if not _port_open():
        return False
    try:
        return _proxy(timeout).get_domain_id() == domain_id()
    except (OSError, xmlrpc.client.Error):
        return False


def spawn_daemon(on_demand: bool = False) -> bool:
    """Start the daemon in the background; False if one already holds the port.

    on_demand: started by a verb rather than `ros2 daemon start`; such a daemon also exits
    once it has been alone in its domain for a while (see server.ALONE_TIMEOUT).

    The listening socket is bound here and handed to the child, so two callers racing to start
    a daemon cannot both succeed, and clients may connect before the child serves.
    """
    listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            listener.bind(('127.0.0.1', daemon_port()))
        except OSError:
            return False
        listener.listen(32)
        subprocess.Popen(
            [sys.executable, '-m', 'ros2cli.daemon.server', '--ros-domain-id', str(domain_id()),
             '--fd', str(listener.fileno()), *(['--exit-when-alone'] if on_demand else [])],
            pass_fds=[listener.fileno()], start_new_session=True, stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=dict(os.environ))
        return True
    finally:
        listener.close()


def wait_until(condition: Callable[[], object], timeout: float = READY_TIMEOUT) -> bool:
    """Poll condition() every 50 ms: True once it holds, False when timeout seconds have passed first."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def shutdown_daemon() -> bool:
    """Ask the daemon to exit; True once its port is free again (after its participant left the graph)."""
    try:
        _proxy(READY_TIMEOUT).system.shutdown()
    except (OSError, xmlrpc.client.Error):
        pass
    return wait_until(lambda: not _port_open())


class DaemonGraph:
    """The daemon's GraphQueries, called over XML-RPC: same methods, same plain answers."""

    def __init__(self, timeout: float = 10.0) -> None:
        self._proxy = _proxy(timeout)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._proxy, name)
