"""The system tests' view of ROS: processes in a private domain plus an rclpy probe node.

`ros` (the fixture in conftest.py) is a RosHarness: start installed executables with
ros.run(package, executable, *args), then talk to them over real DDS through ros.probe, an rclpy
node in the same private domain, spun by a background thread.
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import owl_common.probe
from owl_common.processes import RosSandbox
from rcl_interfaces.msg import SetParametersResult
from rcl_interfaces.srv import GetParameters, SetParameters
from rclpy.parameter import Parameter as RclpyParameter
from rclpy.parameter import parameter_value_to_python

# Seconds before a parameter request is sent again (see Probe.call).
PARAMETER_RESEND = 2.0


class Probe(owl_common.probe.Probe):
    """The test's own rclpy node in the sandbox's domain, with waits and calls that fail a test."""

    def __init__(self, domain_id: int, name: str = 'owl_test_probe'):
        super().__init__(domain_id, name)

    def wait_for_node(self, name: str, timeout: float = 10.0) -> None:
        """Wait until a node of that name (no namespace) is in the graph."""
        wait_until(lambda: name in self.node.get_node_names(), timeout, f'node {name}')

    def wait_until_spinning(self, name: str, timeout: float = 10.0) -> None:
        """Wait until the node (no namespace) answers on its parameter services.

        A node is in the graph from the first line of its constructor, and a Ctrl-C there fails the rest of
        it ("rcl node's context is invalid"); a node that answers has been built and spins, which is where a
        user's Ctrl-C lands.
        """
        self.wait_for_node(name, timeout)
        self.get_parameters(f'/{name}', 'use_sim_time', timeout=timeout)

    def call(self, srv_type: Any, service: str, request: Any, timeout: float = 10.0,
             resend_every: float | None = None) -> Any:
        """Call a service and return the response (waits for the server first).

        With resend_every (idempotent requests only), the request goes out again when no response
        came within that many seconds: right after start-up the server may not have discovered
        this client yet, and then DDS drops the request or the response.
        """
        client = self.node.create_client(srv_type, service)
        try:
            if not client.wait_for_service(timeout_sec=timeout):
                raise AssertionError(f'service {service} did not appear within {timeout} s')
            deadline = time.monotonic() + timeout
            while True:
                future = client.call_async(request)
                attempt = min(resend_every or timeout, deadline - time.monotonic())
                try:
                    wait_until(future.done, attempt, f'response from {service}')
                    return future.result()
                except AssertionError:
                    client.remove_pending_request(future)
                    if time.monotonic() >= deadline:
                        raise AssertionError(
                            f'timed out after {timeout} s waiting for response from {service}') from None
        finally:
            self.node.destroy_client(client)

    def set_parameters(self, node: str, timeout: float = 10.0, **values: Any) -> list[SetParametersResult]:
        """Set parameters of another node through its set_parameters service, one result each."""
        request = SetParameters.Request(
            parameters=[RclpyParameter(k, value=v).to_parameter_msg() for k, v in values.items()])
        return list(self.call(SetParameters, f'{node}/set_parameters', request, timeout,
                              resend_every=PARAMETER_RESEND).results)

    def get_parameters(self, node: str, *names: str, timeout: float = 10.0) -> list[Any]:
        """Current values of another node's parameters, as Python values."""
        response = self.call(GetParameters, f'{node}/get_parameters',
                             GetParameters.Request(names=list(names)), timeout,
                             resend_every=PARAMETER_RESEND)
        return [parameter_value_to_python(v) for v in response.values]


def holds_within(condition: Callable[[], object], timeout: float) -> bool:
    """Whether condition holds within timeout s (looked at every 20 ms)."""
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.02)
    return True


def wait_until(condition: Callable[[], object], timeout: float, what: str) -> None:
    if not holds_within(condition, timeout):
        raise AssertionError(f'timed out after {timeout} s waiting for {what}')


class RosHarness(RosSandbox):
    """A RosSandbox whose probe node is created on first use."""

    def __init__(self) -> None:
        super().__init__()
        # Programs without a display write no headless windows (OWL_WINDOWS_DIR set and empty) unless a
        # test gives them a folder: a suite's turtlesims and cameras would fill the user's own folder,
        # which `owl windows` shows, and spend the machine on frames nobody sees.
        self.env['OWL_WINDOWS_DIR'] = ''
        # The robot view's recordings go to a folder of the test's, not the user's ~/owl_recordings.
        self.recordings = Path(tempfile.mkdtemp(prefix='owl-recordings-'))
        self.env['OWL_RECORDINGS'] = str(self.recordings)
        self._probe: Probe | None = None

    @property
    def probe(self) -> Probe:
        if self._probe is None:
            self._probe = Probe(self.domain_id)
        return self._probe

    def close_probe(self) -> None:
        """Close the probe node; the next use makes a new one (with none of this one's subscriptions)."""
        if self._probe is not None:
            self._probe.close()
            self._probe = None

    def close(self) -> None:
        self.close_probe()
        super().close()
        shutil.rmtree(self.recordings, ignore_errors=True)

    @contextmanager
    def turn(self) -> Iterator[RosHarness]:
        """One test's turn in a world that a module's tests share (a kit started once).

        The test gets a probe of its own (the one that saw the world start is closed first).
        Afterwards the processes the test started are stopped, and its probe (with every subscription
        it made) is closed.
        """
        self.close_probe()
        started = len(self.processes)
        try:
            yield self
        finally:
            for process in reversed(self.processes[started:]):
                if process.running():
                    process.stop(timeout=3.0)
            del self.processes[started:]
            self.close_probe()


# -- helpers for module tests (olive_sim) --------------------------------------------------------

def wait_for_messages(received: list[Any], count: int, timeout: float = 15.0, what: str = 'messages') -> None:
    """Wait until a list filled by Probe.collect holds at least count messages."""
    wait_until(lambda: len(received) >= count, timeout, f'{count} {what} (got {len(received)})')


def wait_for_quiet(received: list[Any], quiet: float, timeout: float = 15.0, what: str = 'messages') -> int:
    """Wait until a list filled by Probe.collect has grown by nothing for quiet seconds; its length then.

    A node's log line can reach the test before the messages the node published just before it: they
    travel through DDS and the probe's executor, the line through a pipe.
    """
    last = (len(received), time.monotonic())

    def settled() -> bool:
        nonlocal last
        now = time.monotonic()
        if len(received) != last[0]:
            last = (len(received), now)
        return now - last[1] >= quiet

    wait_until(settled, timeout, f'no new {what} for {quiet} s (got {len(received)})')
    return last[0]


def endpoints(probe: Probe, topic: str, kind: str = 'publishers', count: int = 1,
              timeout: float = 15.0) -> list[Any]:
    """The graph's TopicEndpointInfo list of a topic's publishers or subscriptions, once it has count.

    Only endpoints whose node is known count: an endpoint can be discovered before its participant's
    node names.
    """
    lookup = (probe.node.get_publishers_info_by_topic if kind == 'publishers'
              else probe.node.get_subscriptions_info_by_topic)

    def known() -> list[Any]:
        return [info for info in lookup(topic) if info.node_name != '_NODE_NAME_UNKNOWN_']

    wait_until(lambda: len(known()) >= count, timeout, f'{count} {kind} of {topic}')
    return known()


def list_parameter_names(probe: Probe, node: str, timeout: float = 10.0) -> list[str]:
    """Names of all parameters of another node, through its list_parameters service."""
    from rcl_interfaces.srv import ListParameters
    response = probe.call(ListParameters, f'{node}/list_parameters', ListParameters.Request(), timeout,
                          resend_every=PARAMETER_RESEND)
    return sorted(response.result.names)

# Longer than launch's own escalation (SIGTERM 5 s after SIGINT, SIGKILL 5 s later), so a test
# stopping `ros2 launch` never races it: a slow child shows up in launch's log, not as a SIGTERM here.
LAUNCH_STOP_TIMEOUT = 15.0


# Runs a Python executable (argv[1:]) as it is, except that destroying an rclpy node and interpreter
# exit never end: stand-ins for a Fast DDS deadlock while a participant is torn down
# (eProsima/Fast-DDS#6502), which happens in destroy_node or, for a node left behind, at exit.
HUNG_TEARDOWN = """
import atexit, runpy, sys, time
from rclpy.node import Node

def destroy_node(self):
    time.sleep(60)

Node.destroy_node = destroy_node
atexit.register(time.sleep, 60)
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name='__main__')
"""


def with_hung_teardown(executable: Path | str, *args: str) -> list[str]:
    """The argv that runs an installed Python executable with its clean-up hanging (see HUNG_TEARDOWN)."""
    return [sys.executable, '-c', HUNG_TEARDOWN, str(executable), *args]
