"""The template every check of `owl check` shares: the Session, the kit's names and common helpers.

A Session holds the processes of a check in a private ROS domain and the probe node that watches
and drives them; beside it are the kit's names as the checks use them, and the helpers more than
one section needs.

A check drives the student's node only through the course's names (topics, types, QoS, services,
parameters), prints each criterion as one JSON line as soon as it is decided (Session.add), and
leaves everything it started to Session.close.
"""

from __future__ import annotations

import json
import os
import signal
import tempfile
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

from olive_kit.description import CAMERA_NAMESPACE, IMU_NAMESPACE, SERVO_RANGES, node_name
from owl_common.probe import Probe
from owl_common.processes import RosProcess, RosSandbox
from rcl_interfaces.srv import GetParameters, ListParameters, SetParameters
from rclpy.parameter import Parameter, parameter_value_to_python

from owl_cli.check import criteria as judge
from owl_cli.check.report import RESULT_PREFIX, WORKSPACE_VARIABLE, Criterion

if TYPE_CHECKING:
    from rclpy.publisher import Publisher
    from rclpy.qos import QoSProfile
    from rclpy.topic_endpoint_info import TopicEndpointInfo

IMU_COMMAND_TOPIC = f"/{node_name('imu', IMU_NAMESPACE)}/true_orientation"  # imu_sim's motion:=command
CMD_VEL = '/turtle1/cmd_vel'
COURSE_CMD_VEL = '/turtle/cmd_vel'  # section 4.3.2's text; turtlesim's turtle is turtle1
CAMERA_NODE = node_name('camera', CAMERA_NAMESPACE)
PAN_RANGE = SERVO_RANGES['pan']
TILT_RANGE = SERVO_RANGES['tilt']  # the camera bracket's
START_TIMEOUT = 15.0  # s for a student's endpoint or behaviour, from its node being up
# s for the student's program to bring up its first node: Python's and rclpy's imports take 1 s on an
# idle machine but eight times that on a loaded one (a class's shared server, a CI host), and the
# waits after it should not pay for that.
NODE_START_LIMIT = 60.0
STOP_TIMEOUT = 8.0  # s for Ctrl-C to end a student's node
PROBE_NODE = 'owl_check'
# The simulated modules serve no web page during a check: a page binds the module's fixed address
# (127.42.0.N), which the student's own kit may hold, and nobody watches it here.
NO_WEB_PAGE = ('-p', 'web_port:=0')  # after --ros-args


def headless(windows: Path) -> dict[str, str | None]:
    """The environment of a student's windowed node run without a display, its windows seen in windows."""
    return {'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1', 'OWL_WINDOWS_DIR': str(windows)}


STANDARD_PARAMETERS = ('use_sim_time', 'qos_overrides.', 'start_type_description_service')


class Failed(Exception):
    """A criterion failed in a way that leaves the rest of the check nothing to look at."""


class Session:
    """The processes of one check and the probe node that watches and drives them."""

    def __init__(self) -> None:
        self.sandbox = RosSandbox()
        self.probe = Probe(self.sandbox.domain_id, PROBE_NODE)
        self.node = self.probe.node
        self.student_process: RosProcess | None = None
        self.imu_command_publisher: Publisher | None = None  # hold_imu's, made on its first call
        self.helpers: dict[str, RosProcess] = {}
        self.decided = 0
        self.stopped = False  # set at our Ctrl-C: an exit after it is no crash
        self.temporary = tempfile.TemporaryDirectory(prefix='owl-check-')

    # -- results ---------------------------------------------------------------------------------

    def add(self, criterion: Criterion) -> bool:
        """Hand the decided criterion to `owl check` (one line on stdout) and return whether it passed.

        When it failed and the student's node has ended by itself, the hint also tells how it ended.
        """
        process = self.student_process
        if not criterion.passed and process is not None and not self.stopped and not process.running():
            criterion.hint = (f'{criterion.hint}; ' if criterion.hint else '') + self.student_exit()
        print(RESULT_PREFIX + json.dumps(criterion.__dict__), flush=True)
        self.decided += 1
        return criterion.passed

    def require(self, criterion: Criterion) -> None:
        """Add the criterion; raise Failed when it failed, for one the rest of the check depends on."""
        if not self.add(criterion):
            raise Failed(criterion.text)

    def student_exit(self) -> str:
        """How the student's node ended, for a hint: its exit code and its last lines of output."""
        process = self.student_process
        assert process is not None
        return (
            f'your node ended with exit code {process.popen.poll()}; its last lines: '
            f'{judge.tail_lines(process.output)}'
        )

    # -- processes -------------------------------------------------------------------------------

    def helper(self, package: str, executable: str, *args: str, env: dict | None = None) -> RosProcess:
        """Start a node the check needs, like `ros2 run package executable args`; kept in helpers."""
        process = self.sandbox.run(package, executable, *args, env=env)
        self.helpers[executable] = process
        return process

    def kit(self, *modules: str, imu_command: bool = False, scene: dict[str, object] | None = None) -> None:
        """The simulated modules: 'imu', 'pan', 'tilt', 'camera' (nodes are waited for).

        scene: the camera's scene parameters (scene, ball_speed, ball_azimuth, gesture, ...).
        """
        nodes = []
        if 'imu' in modules:
            motion = 'command' if imu_command else 'scripted'
            self.helper('olive_sim', 'imu_sim', '--ros-args', '-p', f'motion:={motion}', '-p', 'seed:=1',
                        '-p', 'orientation_noise:=0.0', *NO_WEB_PAGE)
            nodes.append(node_name('imu', IMU_NAMESPACE))
        for servo, (low, high) in (('pan', PAN_RANGE), ('tilt', TILT_RANGE)):
            if servo in modules:
                servo_args = ('-p', f'namespace:={servo}', '-p', f'min_position:={low}',
                              '-p', f'max_position:={high}')
                process = self.sandbox.run('olive_sim', 'servo_sim', '--ros-args', *servo_args, *NO_WEB_PAGE,
                                           label=f'servo {servo}')
                self.helpers[servo] = process
                nodes.append(node_name('servo', servo))
        if 'camera' in modules:
            settings = [arg for name, value in (scene or {}).items() for arg in ('-p', f'{name}:={value}')]
            self.helper('olive_sim', 'camera_sim', '--ros-args', *settings, *NO_WEB_PAGE)
            nodes.append(node_name('camera', CAMERA_NAMESPACE))
        for name in nodes:

            def started(n: str = name) -> bool:
                return n in self.node.get_node_names()

            if not self.wait(started, 30.0):
                raise RuntimeError(f'the simulated kit did not start ({name})')

    def student(self, package: str, executable: str, *args: str, env: dict | None = None) -> RosProcess:
        """`ros2 run package executable args` from the student's workspace."""
        return self.start_student(['ros2', 'run', package, executable, *args], executable, env)

    def student_launch(self, package: str, launch_file: str, env: dict | None = None) -> RosProcess:
        """`ros2 launch package launch_file` from the student's workspace (in env, None unsets a variable)."""
        return self.start_student(['ros2', 'launch', package, launch_file], launch_file, env)

    def start_student(self, argv: list[str], label: str, env: dict | None) -> RosProcess:
        """Start the student's command and wait until a node of it is up (or it has ended).

        The checks' waits then count from the student's code running, not from Python starting.
        """
        before = self.graph_nodes()
        self.student_process = self.sandbox.command(argv, label=label, env=env)
        self.wait(lambda: bool(self.graph_nodes() - before), NODE_START_LIMIT)
        return self.student_process

    def stop_student(
        self, text: str = 'Ctrl-C stops the node cleanly (exit code 0, no traceback)', launch: bool = False
    ) -> None:
        """Press Ctrl-C on the student's node and add the criterion text: it ends cleanly in time.

        Cleanly is exit code 0 and no traceback within STOP_TIMEOUT s. With launch the signal goes
        to `ros2 launch` alone, which passes it on to its nodes; else to the whole process group.
        """
        process = self.student_process
        assert process is not None
        if not process.running():
            self.add(Criterion(text, False, 'the node was no longer running at Ctrl-C'))
            return
        self.stopped = True
        if launch:  # ros2 launch without a terminal passes Ctrl-C on to its nodes itself
            os.kill(process.pid, signal.SIGINT)
        else:
            process.send_signal(signal.SIGINT)
        try:
            code = process.wait(STOP_TIMEOUT)
        except Exception:
            process.stop(2.0)
            self.add(
                Criterion(
                    text,
                    False,
                    f'still running {STOP_TIMEOUT:g} s after Ctrl-C: catch '
                    'KeyboardInterrupt around rclpy.spin and let main() return',
                )
            )
            return
        traceback = 'Traceback' in process.output
        self.add(
            Criterion(
                text,
                code == 0 and not traceback,
                (
                    f'exit code {code}{" with a traceback" if traceback else ""}: wrap rclpy.spin in '
                    'try/except KeyboardInterrupt, then destroy_node() and rclpy.shutdown(); last lines: '
                    f'{judge.tail_lines(process.output)}'
                ),
                f'exit code {code}',
            )
        )

    def close(self) -> None:
        """Stop everything the check started: its processes, the probe node and its temporary folder."""
        # Ctrl-C to every process at once: the sandbox then waits for each in turn, and the kit's
        # modules end together (0.4 s for four, where one after the other took 2.7 s).
        for process in self.sandbox.processes:
            process.send_signal(signal.SIGINT)
        try:
            self.probe.close()
        finally:
            self.sandbox.close()
            self.temporary.cleanup()

    # -- waiting and the graph -------------------------------------------------------------------

    def wait(self, condition: Callable[[], bool], timeout: float) -> bool:
        """Wait for condition; False at the timeout or as soon as the student's node has exited.

        It is looked at after 5, 10, 20, 40 ms, then every 50 ms (poll_intervals): most waits (a
        service call's answer, a client that matches its server) end within a few ms.
        """
        deadline = time.monotonic() + timeout
        intervals = poll_intervals()
        while not condition():
            process = self.student_process
            if time.monotonic() > deadline or (process is not None and not process.running()):
                return condition()
            time.sleep(next(intervals))
        return True

    def graph_nodes(self) -> set[bytes]:
        """The nodes that may be the student's, by their /rosout publisher's id (unique where names repeat).

        By name, a node started a second time looks old while the first run's lingers in the graph.
        Left out: the kit's, the probe's, `ros2 launch`'s own and hidden ones (a `ros2` daemon's),
        which discovery may report only after the student's program has started.
        """
        return {
            bytes(info.endpoint_gid)
            for info in self.node.get_publishers_info_by_topic('/rosout')
            if info.node_name != PROBE_NODE and not info.node_name.startswith(('launch_ros_', '_', 'olive_'))
        }

    def endpoints(self, topic: str, kind: str) -> list[TopicEndpointInfo]:
        """The student's publishers (kind 'publishers') or else subscriptions on topic.

        The probe's own endpoints and the simulated kit's (nodes named olive_*) are left out.
        """
        lookup = (
            self.node.get_publishers_info_by_topic
            if kind == 'publishers'
            else self.node.get_subscriptions_info_by_topic
        )
        return [
            info
            for info in lookup(topic)
            if info.node_name not in (PROBE_NODE, '_NODE_NAME_UNKNOWN_')
            and not info.node_name.startswith('olive_')
        ]

    def expect_endpoint(
        self, topic: str, kind: str, type_name: str, hint: str, timeout: float = START_TIMEOUT
    ) -> TopicEndpointInfo | None:
        """Wait for the student's endpoint of kind on topic and add the criterion that it has type_name.

        The endpoint when it passed, else None; hint explains a failure when none shows up in timeout s.
        """
        verb = 'publishes' if kind == 'publishers' else 'subscribes to'
        text = f'{verb} {type_name} on {topic}'
        self.wait(lambda: bool(self.endpoints(topic, kind)), timeout)
        found = self.endpoints(topic, kind)
        if not found:
            self.add(Criterion(text, False, hint))
            return None
        types = sorted({info.topic_type for info in found})
        return (
            found[0]
            if self.add(
                Criterion(
                    text, type_name in types, f'the type is {", ".join(types)}', f'node {found[0].node_name}'
                )
            )
            else None
        )

    def collect(self, msg_type: Any, topic: str, qos: QoSProfile | int = 10) -> list[tuple[float, Any]]:
        """(monotonic arrival time, message) of every message from now on."""
        received: list[tuple[float, Any]] = []
        self.node.create_subscription(msg_type, topic, lambda m: received.append((time.monotonic(), m)), qos)
        return received

    def call(self, srv_type: Any, service: str, request: Any, timeout: float = 10.0) -> Any | None:
        """The service's response to request; None when it is not ready or does not answer in timeout s."""
        client = self.node.create_client(srv_type, service)
        try:
            if not self.wait(lambda: client.service_is_ready(), timeout):
                return None
            deadline = time.monotonic() + timeout
            while time.monotonic() < deadline:
                future = client.call_async(request)
                # Right after start-up the server may not know this client yet: ask again.
                if self.wait(future.done, min(2.0, deadline - time.monotonic())):
                    return future.result()
                client.remove_pending_request(future)
            return None
        finally:
            self.node.destroy_client(client)

    def parameters(self, node: str) -> list[str]:
        """The names of a node's parameters; [] when its list_parameters service does not answer."""
        response = self.call(ListParameters, f'/{node}/list_parameters', ListParameters.Request())
        return list(response.result.names) if response else []

    def get_parameter(self, node: str, name: str) -> Any:
        """The value of one parameter of a node; None when the node does not answer."""
        return self.get_parameters(node, [name]).get(name)

    def get_parameters(self, node: str, names: list[str]) -> dict[str, Any]:
        """The values of the parameters, in one service call (each call is a round trip)."""
        response = self.call(GetParameters, f'/{node}/get_parameters', GetParameters.Request(names=names))
        if response is None or len(response.values) != len(names):
            return {}
        return {name: parameter_value_to_python(v) for name, v in zip(names, response.values, strict=True)}

    def own_parameters(self, node: str) -> dict[str, Any]:
        """A node's parameters and values, without those rclpy declares for every node."""
        names = [n for n in self.parameters(node) if not n.startswith(STANDARD_PARAMETERS)]
        return self.get_parameters(node, names) if names else {}

    def set_parameter(self, node: str, name: str, value: Any) -> tuple[bool, str]:
        """Set a node's parameter: (successful, reason) as the node answers, or (False, why) without one."""
        request = SetParameters.Request(parameters=[Parameter(name, value=value).to_parameter_msg()])
        response = self.call(SetParameters, f'/{node}/set_parameters', request)
        if response is None:
            return False, f'/{node}/set_parameters did not answer'
        result = response.results[0]
        return result.successful, result.reason


def poll_intervals(first: float = 0.005, longest: float = 0.05) -> Iterator[float]:
    """The pauses between looks at a condition: first, doubling up to longest, then longest for ever."""
    interval = first
    while True:
        yield min(interval, longest)
        interval *= 2


def values_since(
    received: list[tuple[float, Any]], since: float, value: Callable[[Any], float]
) -> list[float]:
    """value(message) of the messages from collect() that arrived at monotonic time since or later."""
    return [value(message) for stamp, message in received if stamp >= since]


def launch_files(package: str) -> list[Path]:
    """The launch files (.py, .xml, .yaml) in the installed package's share/<package>/launch, sorted."""
    from ament_index_python.packages import get_package_share_directory

    folder = Path(get_package_share_directory(package)) / 'launch'
    return sorted(p for p in folder.glob('*') if p.suffix in ('.py', '.xml', '.yaml'))


def workspace() -> Path:
    """The student's workspace as `owl check` hands it over (OWL_CHECK_WORKSPACE), else the current folder."""
    return Path(os.environ.get(WORKSPACE_VARIABLE, '.'))


def client_ended(s: Session, process: RosProcess) -> None:
    """A service client's last criterion: it ends by itself once it has its answer (else it is stopped)."""
    code = process.popen.poll()
    s.add(
        Criterion(
            'ends by itself with exit code 0 after the answer',
            code == 0,
            'after the answer: destroy_node() and rclpy.shutdown(), so main() returns'
            if code is None
            else f'exit code {code}: {judge.tail_lines(process.output)}',
            f'exit code {code}',
        )
    )
    if process.running():
        s.stop_student()
