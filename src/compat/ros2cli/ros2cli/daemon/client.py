"""Talk to the daemon of this ROS domain: is it running, start it, stop it, ask it.

The calls go as JSON over one HTTP/1.0 request each (ros2cli.daemon.JSON_PATH), with no import
of xmlrpc.client or http.client.
"""

import json
import os
import socket
import subprocess
import sys
import time
from collections.abc import Callable
from typing import Any

from ros2cli.daemon import JSON_PATH, daemon_port, domain_id

READY_TIMEOUT = 10.0


class DaemonError(Exception):
    """The daemon gave no answer to the call: not ours, too old for JSON calls, or a broken reply."""


class DaemonFault(DaemonError):
    """The call reached the daemon and failed there: a code and a message, as an XML-RPC fault has."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


def call(method: str, params: list[Any], timeout: float) -> Any:
    """The daemon's answer to method(*params); OSError when it cannot be reached within timeout s."""
    body = json.dumps({'method': method, 'params': params}).encode()
    request = (f'POST {JSON_PATH} HTTP/1.0\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n'
               f'Content-Length: {len(body)}\r\n\r\n').encode() + body
    reply = bytearray()
    with socket.create_connection(('127.0.0.1', daemon_port()), timeout=timeout) as connection:
        connection.sendall(request)
        while chunk := connection.recv(65536):  # HTTP/1.0: the daemon closes after its answer
            reply += chunk
    head, _, payload = bytes(reply).partition(b'\r\n\r\n')
    status = head.split(b'\r\n', 1)[0].split()
    if len(status) < 2 or status[1] != b'200':
        raise DaemonError(f'the daemon answered {head[:40]!r} to {method}')
    try:
        answer = json.loads(payload)
        if 'fault' in answer:
            raise DaemonFault(*answer['fault'])
        return answer['result']
    except (ValueError, KeyError, TypeError):
        raise DaemonError(f'the daemon sent no answer to {method}') from None


def _port_open() -> bool:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.settimeout(0.2)
        return probe.connect_ex(('127.0.0.1', daemon_port())) == 0


def is_daemon_running(timeout: float = 5.0) -> bool:
    """True when this domain's daemon answers (a starting daemon is waited for)."""
    if not _port_open():
        return False
    try:
        return call('get_domain_id', [], timeout) == domain_id()
    except (OSError, DaemonError):
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
        call('system.shutdown', [], READY_TIMEOUT)
    except (OSError, DaemonError):
        pass
    return wait_until(lambda: not _port_open())


class DaemonGraph:
    """The daemon's GraphQueries, called over JSON: same methods, same plain answers (lists for tuples)."""

    def __init__(self, timeout: float = 10.0) -> None:
        self._timeout = timeout

    def __getattr__(self, name: str) -> Callable[..., Any]:
        if name.startswith('__'):
            raise AttributeError(name)
        return lambda *params: call(name, list(params), self._timeout)
