"""The part of `owl check` that drives ROS: one exercise's check in a private ROS domain.

Runs as its own process (`python -m owl_cli.check_ros EXERCISE`), started by `owl check` in a
shell that has sourced the student's workspace, so `ros2 run` finds the student's executables and
this process imports the student's interface types. It starts what the exercise needs (the
simulated kit, turtlesim, a service server) and the student's node in a domain of its own, drives
the node only through the course's names (topics, types, QoS, services, parameters), prints each
criterion as one JSON line as soon as it is decided, and stops everything it started.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import signal
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

# Discovery stays on this machine whatever the student's shell says (set before rclpy starts).
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from owl_common.probe import Probe
from owl_common.processes import RosProcess, RosSandbox
from rcl_interfaces.srv import GetParameters, ListParameters, SetParameters
from rclpy.parameter import Parameter, parameter_value_to_python
from rosidl_runtime_py.utilities import get_service

from owl_cli import check_criteria as judge
from owl_cli import check_workspace as ws
from owl_cli.check_report import RESULT_PREFIX, WORKSPACE_VARIABLE, Criterion

if TYPE_CHECKING:
    from rclpy.publisher import Publisher
    from rclpy.qos import QoSProfile
    from rclpy.topic_endpoint_info import TopicEndpointInfo

IMU_TOPIC = '/olive/imu/x1684267976913/imu'
IMU_COMMAND_TOPIC = '/olive_imu_x1684267976913_dcm_srv/true_orientation'
CMD_VEL = '/turtle1/cmd_vel'
COURSE_CMD_VEL = '/turtle/cmd_vel'  # section 4.3.2's text; turtlesim's turtle is turtle1
CAMERA_TOPIC = '/olive/camera/eye/image/compressed'
PAN_RANGE = (-1.5708, 1.5708)  # the kit's pan servo
TILT_RANGE = (-1.3, 0.9)  # the kit's tilt servo (camera bracket)
START_TIMEOUT = 15.0  # s for a student's node to show up in the graph
STOP_TIMEOUT = 8.0  # s for Ctrl-C to end a student's node
PROBE_NODE = 'owl_check'
# The simulated modules serve no web page during a check: a page binds the module's fixed address
# (127.42.0.N), which the student's own kit may hold, and nobody watches it here.
NO_WEB_PAGE = ('-p', 'web_port:=0')  # after --ros-args


def goal_topic(servo: str) -> str:
    return f'/olive/servo/{servo}/goal/position'


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
        process = self.student_process
        if not criterion.passed and process is not None and not self.stopped and not process.running():
            criterion.hint = (f'{criterion.hint}; ' if criterion.hint else '') + self.student_exit()
        print(RESULT_PREFIX + json.dumps(criterion.__dict__), flush=True)
        self.decided += 1
        return criterion.passed

    def require(self, criterion: Criterion) -> None:
        if not self.add(criterion):
            raise Failed(criterion.text)

    def student_exit(self) -> str:
        process = self.student_process
        assert process is not None
        return (
            f'your node ended with exit code {process.popen.poll()}; its last lines: '
            f'{judge.tail_lines(process.output)}'
        )

    # -- processes -------------------------------------------------------------------------------

    def helper(self, package: str, executable: str, *args: str, env: dict | None = None) -> RosProcess:
        process = self.sandbox.run(package, executable, *args, env=env)
        self.helpers[executable] = process
        return process

    def kit(self, *modules: str, imu_command: bool = False) -> None:
        """The simulated modules: 'imu', 'pan', 'tilt', 'camera' (nodes are waited for)."""
        nodes = []
        if 'imu' in modules:
            motion = 'command' if imu_command else 'scripted'
            self.helper(
                'olive_sim',
                'imu_sim',
                '--ros-args',
                '-p',
                f'motion:={motion}',
                '-p',
                'seed:=1',
                '-p',
                'orientation_noise:=0.0',
                *NO_WEB_PAGE,
            )
            nodes.append('olive_imu_x1684267976913_dcm_srv')
        for servo, (low, high) in (('pan', PAN_RANGE), ('tilt', TILT_RANGE)):
            if servo in modules:
                process = self.sandbox.run(
                    'olive_sim',
                    'servo_sim',
                    '--ros-args',
                    '-p',
                    f'namespace:={servo}',
                    '-p',
                    f'min_position:={low}',
                    '-p',
                    f'max_position:={high}',
                    *NO_WEB_PAGE,
                    label=f'servo {servo}',
                )
                self.helpers[servo] = process
                nodes.append(f'olive_servo_{servo}_dcm_srv')
        if 'camera' in modules:
            self.helper('olive_sim', 'camera_sim', '--ros-args', *NO_WEB_PAGE)
            nodes.append('olive_camera_eye_dcm_srv')
        for name in nodes:

            def started(n: str = name) -> bool:
                return n in self.node.get_node_names()

            if not self.wait(started, 30.0):
                raise RuntimeError(f'the simulated kit did not start ({name})')

    def student(self, package: str, executable: str, *args: str, env: dict | None = None) -> RosProcess:
        """`ros2 run package executable args` from the student's workspace."""
        self.student_process = self.sandbox.command(
            ['ros2', 'run', package, executable, *args], label=executable, env=env
        )
        return self.student_process

    def student_launch(
        self, package: str, launch_file: str, env: dict[str, str | None] | None = None
    ) -> RosProcess:
        self.student_process = self.sandbox.command(
            ['ros2', 'launch', package, launch_file], label=launch_file, env=env
        )
        return self.student_process

    def stop_student(
        self, text: str = 'Ctrl-C stops the node cleanly (exit code 0, no traceback)', launch: bool = False
    ) -> None:
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
        """Wait for condition; False at the timeout or as soon as the student's node has exited."""
        deadline = time.monotonic() + timeout
        while not condition():
            process = self.student_process
            if time.monotonic() > deadline or (process is not None and not process.running()):
                return condition()
            time.sleep(0.05)
        return True

    def endpoints(self, topic: str, kind: str) -> list[TopicEndpointInfo]:
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
        response = self.call(ListParameters, f'/{node}/list_parameters', ListParameters.Request())
        return list(response.result.names) if response else []

    def get_parameter(self, node: str, name: str) -> Any:
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
        request = SetParameters.Request(parameters=[Parameter(name, value=value).to_parameter_msg()])
        response = self.call(SetParameters, f'/{node}/set_parameters', request)
        if response is None:
            return False, f'/{node}/set_parameters did not answer'
        result = response.results[0]
        return result.successful, result.reason


def values_since(
    received: list[tuple[float, Any]], since: float, value: Callable[[Any], float]
) -> list[float]:
    return [value(message) for stamp, message in received if stamp >= since]


# -- chapter 3 -------------------------------------------------------------------------------------


def check_random_number_publisher(s: Session) -> None:
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    s.expect_endpoint(
        '/random_numbers',
        'publishers',
        'std_msgs/msg/Int32',
        "no publisher on random_numbers: create_publisher(Int32, 'random_numbers', 10)",
    )
    s.wait(lambda: len(numbers) >= 5, 12.0)
    values = [m.data for _, m in numbers]
    s.add(
        Criterion(
            'publishes numbers on random_numbers',
            len(values) >= 3,
            'fewer than 3 numbers in 12 s: publish from a timer callback',
            f'{len(values)} numbers',
        )
    )
    if len(values) >= 3:
        per_second = judge.rate([t for t, _ in numbers])
        s.add(
            Criterion(
                'publishes one number per second (create_timer(1.0, ...))',
                0.7 <= per_second <= 1.4,
                'the timer period must be 1.0 s',
                f'{per_second:.2f} per second',
            )
        )
        s.add(judge.in_range('the numbers', values, 1, 100, 'random.randint(1, 100) gives 1..100'))
        s.add(
            Criterion(
                'the numbers are random',
                len(set(values)) > 1,
                'every number is the same: draw a new random.randint(1, 100) in each callback',
                f'{values[:6]}',
            )
        )
    s.stop_student()


def check_upper_limit(s: Session) -> None:
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    node = 'random_number_publisher'
    s.wait(lambda: node in s.node.get_node_names() and len(numbers) >= 1, START_TIMEOUT)
    default = s.get_parameter(node, 'upper_limit')
    s.add(
        Criterion(
            "declares the parameter upper_limit with the default 100 (declare_parameter('upper_limit', 100))",
            default == 100 and not isinstance(default, bool),
            'no parameter upper_limit on /random_number_publisher'
            if default is None
            else 'upper_limit must be the integer 100 at start',
            f'upper_limit = {default!r}',
        )
    )
    ok, reason = s.set_parameter(node, 'upper_limit', 3)
    s.add(Criterion('ros2 param set /random_number_publisher upper_limit 3 succeeds', ok, reason))
    since = time.monotonic() + 0.2
    s.wait(lambda: len(values_since(numbers, since, lambda m: m.data)) >= 4, 8.0)
    values = values_since(numbers, since, lambda m: m.data)
    s.add(
        judge.in_range(
            'the numbers after upper_limit is set to 3',
            values,
            1,
            3,
            'the numbers ignore upper_limit: read it in the timer callback with '
            "self.get_parameter('upper_limit') and use it in random.randint(1, upper_limit)",
        )
    )
    s.stop_student()


def check_random_number_subscriber(s: Session) -> None:
    from std_msgs.msg import Int32

    process = s.student('random_number_ps', 'random_number_subscriber')
    s.expect_endpoint(
        '/random_numbers',
        'subscriptions',
        'std_msgs/msg/Int32',
        "no subscription on random_numbers: create_subscription(Int32, 'random_numbers', callback, 10)",
    )
    publisher = s.node.create_publisher(Int32, '/random_numbers', 10)
    sent = (17, 42, 93)

    def printed() -> bool:
        words = set(process.output.replace(':', ' ').split())
        return all(str(n) in words for n in sent)

    deadline = time.monotonic() + 10.0
    while not printed() and time.monotonic() < deadline and process.running():
        for number in sent:
            publisher.publish(Int32(data=number))
        time.sleep(0.5)
    s.add(
        Criterion(
            'prints every number it receives (17, 42, 93 were published)',
            printed(),
            "log each message in the callback: self.get_logger().info(f'Received: {msg.data}')",
            judge.tail_lines(process.output, 2),
        )
    )
    s.stop_student()


def check_counter_publisher(s: Session) -> None:
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'counter_publisher')
    s.expect_endpoint(
        '/random_numbers',
        'publishers',
        'std_msgs/msg/Int32',
        "no publisher on random_numbers (the random number subscriber's topic)",
    )
    s.wait(lambda: len(numbers) >= 4, 12.0)
    values = [m.data for _, m in numbers]
    steps = {b - a for a, b in itertools.pairwise(values)}
    s.add(
        Criterion(
            'each number is one more than the one before',
            len(values) >= 3 and steps == {1},
            'keep a counter in the node, publish it and add 1 in each timer callback',
            f'{values[:6]}',
        )
    )
    s.stop_student()


def check_turtle_random_velocity(s: Session) -> None:
    from geometry_msgs.msg import Twist
    from turtlesim.msg import Pose

    s.helper('turtlesim', 'turtlesim_node', env={'DISPLAY': None, 'WAYLAND_DISPLAY': None})
    poses = s.collect(Pose, '/turtle1/pose')
    twists = s.collect(Twist, CMD_VEL)
    s.student('random_number_ps', 'turtle_random_velocity')
    s.expect_endpoint(
        CMD_VEL, 'publishers', 'geometry_msgs/msg/Twist', "no publisher on turtlesim's /turtle1/cmd_vel"
    )
    s.wait(lambda: len(twists) >= 3, 12.0)
    pairs = {(round(m.linear.x, 3), round(m.angular.z, 3)) for _, m in twists}
    s.add(
        Criterion(
            'the velocities are random (linear.x and angular.z change)',
            len(pairs) >= 2,
            'draw new random numbers in each callback',
            f'{len(twists)} velocities',
        )
    )
    def farthest() -> float:  # from where the turtle was first seen
        return max((math.dist((poses[0][1].x, poses[0][1].y), (p.x, p.y)) for _, p in poses), default=0.0)

    s.wait(lambda: farthest() > 0.2, 5.0)
    distance = farthest()
    s.add(
        Criterion(
            'the turtle moves',
            distance > 0.2,
            'publish non-zero velocities on /turtle1/cmd_vel',
            f'{distance:.2f} m',
        )
    )
    s.stop_student()


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


def check_temp_client(s: Session) -> None:
    from olive_interfaces.srv import TempConv

    requests = []

    def answer(request: Any, response: Any) -> Any:
        requests.append(request.temp_c)
        response.temp_k = request.temp_c + 273.15
        response.temp_f = request.temp_c * 9 / 5 + 32
        return response

    s.node.create_service(TempConv, '/temp_conversion', answer)
    process = s.student('olive_srvcli', 'temp_client', '100')
    s.wait(lambda: not process.running(), 15.0)
    s.add(
        Criterion(
            'sends the command-line value as temp_c (temp_client 100 asks for 100.0)',
            100.0 in requests,
            "float(sys.argv[1]) goes into the request's temp_c",
            f'requests {requests}',
        )
    )
    s.add(
        Criterion(
            "prints the server's answer (373.15 Kelvin and 212.0 Fahrenheit)",
            '373.15' in process.output and '212.0' in process.output,
            'log response.temp_k and response.temp_f',
            judge.tail_lines(process.output, 1),
        )
    )
    client_ended(s, process)


def check_lower_limit(s: Session) -> None:
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    node = 'random_number_publisher'
    s.wait(lambda: node in s.node.get_node_names(), START_TIMEOUT)
    names = [n for n in s.parameters(node) if 'lower' in n or 'min' in n]
    if not s.add(
        Criterion(
            'declares a parameter for the lower bound (e.g. lower_limit)',
            bool(names),
            "declare_parameter('lower_limit', 1) beside upper_limit",
            ', '.join(names),
        )
    ):
        s.stop_student()
        return
    ok_upper, reason_upper = s.set_parameter(node, 'upper_limit', 12)
    ok_lower, reason_lower = s.set_parameter(node, names[0], 10)
    s.add(
        Criterion(
            f'ros2 param set of upper_limit 12 and {names[0]} 10 succeed',
            ok_upper and ok_lower,
            reason_upper or reason_lower,
        )
    )
    since = time.monotonic() + 0.2
    s.wait(lambda: len(values_since(numbers, since, lambda m: m.data)) >= 4, 8.0)
    s.add(
        judge.in_range(
            f'the numbers after {names[0]} 10 and upper_limit 12',
            values_since(numbers, since, lambda m: m.data),
            10,
            12,
            f'read {names[0]} in the timer callback and use it in random.randint({names[0]}, upper_limit)',
        )
    )
    s.stop_student()


def launch_files(package: str) -> list[Path]:
    from ament_index_python.packages import get_package_share_directory

    folder = Path(get_package_share_directory(package)) / 'launch'
    return sorted(p for p in folder.glob('*') if p.suffix in ('.py', '.xml', '.yaml'))


def check_turtle_launch(s: Session) -> None:
    files = launch_files('olive_launch')
    names = [f.name for f in files]
    chosen = next(
        (n for n in ('turtle_launch.py', 'turtle.launch.py') if n in names), names[0] if names else None
    )
    if not s.add(
        Criterion(
            'olive_launch installs a launch file (share/olive_launch/launch)',
            chosen is not None,
            "add (os.path.join('share', package_name, 'launch'), glob(...)) to data_files in setup.py",
            ', '.join(names),
        )
    ) or chosen is None:  # (add() is False when chosen is None; the test tells mypy so)
        return
    s.student_launch('olive_launch', chosen)
    s.wait(lambda: {'turtle1', 'turtle2'} <= set(s.node.get_node_names()), 20.0)
    running = sorted(set(s.node.get_node_names()) & {'turtle1', 'turtle2'})
    s.add(
        Criterion(
            f'ros2 launch olive_launch {chosen} starts two turtlesim nodes named turtle1 and turtle2',
            running == ['turtle1', 'turtle2'],
            "two Node(package='turtlesim', executable='turtlesim_node', name=...) actions",
            f'{running}',
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)


def check_imu_turtle_launch(s: Session) -> None:
    from turtlesim.msg import Pose

    files = [
        f for f in launch_files('olive_imu') if 'imu_turtle' in f.read_text() and 'turtlesim' in f.read_text()
    ]
    if not s.add(
        Criterion(
            'olive_imu installs a launch file that names turtlesim and imu_turtle',
            bool(files),
            'a launch file in olive_imu/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files),
        )
    ):
        return
    s.kit('imu')  # the scripted motion: pitch and yaw sweep
    poses = s.collect(Pose, '/turtle1/pose')
    s.student_launch('olive_imu', files[0].name)
    s.wait(lambda: len(poses) >= 10, 20.0)
    start = (poses[0][1].x, poses[0][1].y) if poses else None
    s.wait(lambda: start is not None and math.dist(start, (poses[-1][1].x, poses[-1][1].y)) > 0.2, 10.0)
    distance = math.dist(start, (poses[-1][1].x, poses[-1][1].y)) if start else 0.0
    s.add(
        Criterion(
            f'ros2 launch olive_imu {files[0].name} starts turtlesim and the IMU drives the turtle',
            distance > 0.2,
            'no turtle pose arrived' if start is None else 'the turtle did not move',
            f'{distance:.2f} m',
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)


STANDARD_PARAMETERS = ('use_sim_time', 'qos_overrides.', 'start_type_description_service')


def check_imu_turtle_speed(s: Session) -> None:
    from geometry_msgs.msg import Twist

    s.kit('imu', imu_command=True)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle')
    s.wait(lambda: len(twists) >= 3 and 'imu_turtle' in s.node.get_node_names(), START_TIMEOUT)

    def speed() -> float:
        return judge.mean([v[0] for v in settle(s, twists, 0.0, 0.4, 0.0, lambda m: (m.linear.x,), 1.2)])

    before = speed()
    found, detail = None, []
    for name, value in s.own_parameters('imu_turtle').items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            continue
        changed = type(value)(value * 2 if value else 1)
        ok, _ = s.set_parameter('imu_turtle', name, changed)
        if not ok:
            continue
        after = speed()
        s.set_parameter('imu_turtle', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.2f}->{after:.2f} m/s')
        if abs(before) > judge.STILL and abs(after - before) > 0.3 * abs(before):
            found = name
            break
    s.add(
        Criterion(
            "a parameter changes the turtle's speed while it runs (ros2 param set)",
            found is not None,
            "declare_parameter('speed', 1.0) and multiply linear.x by self.get_parameter('speed').value "
            'in the callback',
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()


# -- section 3.6 -------------------------------------------------------------------------------------


def check_temp_server(s: Session) -> None:
    from olive_interfaces.srv import TempConv

    s.student('olive_srvcli', 'temp_server')
    s.wait(
        lambda: any(name == '/temp_conversion' for name, _ in s.node.get_service_names_and_types()),
        START_TIMEOUT,
    )
    types = dict(s.node.get_service_names_and_types()).get('/temp_conversion')
    if not s.add(
        Criterion(
            'offers the service temp_conversion of type olive_interfaces/srv/TempConv',
            types == ['olive_interfaces/srv/TempConv'],
            "create_service(TempConv, 'temp_conversion', callback)"
            if types is None
            else f'its type is {types}',
        )
    ):
        s.stop_student()
        return
    for temp_c in (0.0, 100.0):
        response = s.call(TempConv, '/temp_conversion', TempConv.Request(temp_c=temp_c))
        if response is None:
            s.add(
                Criterion(
                    f'temp_conversion answers {temp_c:g} °C',
                    False,
                    'no answer in 10 s: the callback must return the response',
                )
            )
            continue
        s.add(judge.kelvin(temp_c, response.temp_k))
        s.add(judge.fahrenheit(temp_c, response.temp_f))
    s.stop_student()


# -- section 4.3 -------------------------------------------------------------------------------------


def hold_imu(s: Session, roll: float, pitch: float, yaw: float) -> None:
    from geometry_msgs.msg import Quaternion
    from owl_common.quaternion import from_euler

    x, y, z, w = from_euler(roll, pitch, yaw)
    publisher = s.imu_command_publisher
    if publisher is None:
        publisher = s.imu_command_publisher = s.node.create_publisher(Quaternion, IMU_COMMAND_TOPIC, 10)
    publisher.publish(Quaternion(x=x, y=y, z=z, w=w))


def settle(
    s: Session,
    received: list,
    roll: float,
    pitch: float,
    yaw: float,
    value: Callable[[Any], tuple[float, ...]],
    seconds: float = 1.0,
) -> list[tuple[float, ...]]:
    """Hold the IMU there (sent again each 0.2 s), and return what the node sent in the last half."""
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        hold_imu(s, roll, pitch, yaw)
        time.sleep(0.2)
    since = start + seconds / 2
    return [value(m) for t, m in received if t >= since]


def check_imu_turtle(s: Session) -> None:
    from geometry_msgs.msg import Twist

    s.kit('imu', imu_command=True)
    hold_imu(s, 0.0, 0.0, 0.0)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle')
    s.expect_endpoint(
        IMU_TOPIC, 'subscriptions', 'sensor_msgs/msg/Imu', f"no subscription on the IMU's topic {IMU_TOPIC}"
    )
    hint = 'no publisher on /turtle1/cmd_vel: the turtle of turtlesim is turtle1'
    if s.endpoints(COURSE_CMD_VEL, 'publishers'):
        hint = (
            "you publish on /turtle/cmd_vel (the course's text), but turtlesim's turtle is turtle1: "
            'publish on /turtle1/cmd_vel'
        )
    if s.expect_endpoint(CMD_VEL, 'publishers', 'geometry_msgs/msg/Twist', hint) is None:
        s.stop_student()
        return
    if not s.wait(lambda: len(twists) >= 3, 10.0):
        s.add(
            Criterion(
                'publishes velocities while the IMU sends data',
                False,
                'no Twist on /turtle1/cmd_vel in 10 s: publish one for each IMU message (or from a timer)',
            )
        )
        s.stop_student()
        return

    def velocity(m: Any) -> tuple[float, float]:
        return m.linear.x, m.angular.z

    for roll, pitch, yaw, motion in ((0.0, 0.0, 0.0, None), (0.0, 0.4, 0.0, 'pitch'), (0.0, 0.0, 0.5, 'yaw')):
        sent = settle(s, twists, roll, pitch, yaw, velocity, 1.2)
        linear = judge.mean([v[0] for v in sent])
        angular = judge.mean([v[1] for v in sent])
        if not sent:
            s.add(
                Criterion(
                    f'the turtle answers the IMU ({motion or "level"})',
                    False,
                    'no velocity arrived while the IMU held still for 1 s',
                )
            )
        elif motion is None:
            s.add(judge.standing_still(linear, angular))
        else:
            s.add(judge.turtle_response(motion, linear, angular))
    s.stop_student()


# -- section 4.4 -------------------------------------------------------------------------------------

TORQUE_OFF_WARNING = 'ignored, torque is disabled'


def torque_criterion(s: Session, servo: str, goals: list) -> None:
    log = s.helpers[servo].output
    enabled = 'torque enabled' in log
    early = TORQUE_OFF_WARNING in log
    if not enabled:
        hint = (
            f'the {servo} servo ignores every goal while its torque is off: call '
            f'/olive/servo/{servo}/setTorqueEnable (std_srvs/srv/Trigger) before the first goal'
        )
    else:
        hint = (
            f'goals reached the {servo} servo before its torque was on and were ignored: call '
            'setTorqueEnable and wait for its answer before publishing goals'
        )
    s.add(
        Criterion(
            f'enables the {servo} torque (setTorqueEnable) before sending goals',
            enabled and not early,
            hint,
            f'{len(goals)} goals',
        )
    )


def joint_positions(s: Session, servo: str) -> list:
    from sensor_msgs.msg import JointState

    return s.collect(JointState, f'/olive/servo/{servo}/joint')


def moved(joints: list, since: float = 0.0) -> float:
    values = [m.position[0] for t, m in joints if t >= since and m.position]
    return max(values) - min(values) if values else 0.0


def check_control_servo(s: Session, torque_off_only: bool = False) -> None:
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'control_servo')
    if not torque_off_only:
        s.expect_endpoint(
            goal_topic('pan'), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic("pan")}'
        )
    s.wait(lambda: len(goals) >= 20, START_TIMEOUT)
    start = time.monotonic()
    s.wait(lambda: judge.oscillates([m.data for _, m in goals]), 8.0)
    if torque_off_only:
        s.wait(lambda: 'torque enabled' in s.helpers['pan'].output, 2.0)
    else:
        values = [m.data for _, m in goals]
        per_second = judge.rate([t for t, _ in goals if t >= start])
        s.add(
            Criterion(
                'publishes goals at least 10 times per second (the course starts at every 0.01 s)',
                per_second >= 10.0,
                'publish from create_timer(0.01, ...)',
                f'{per_second:.0f} per second',
            )
        )
        s.add(
            Criterion(
                'the goals follow a sine (they swing and turn back)',
                judge.oscillates(values),
                'add a small step to a variable in each callback and publish math.sin(variable)',
                f'{len(values)} goals from {min(values, default=0):+.2f} to {max(values, default=0):+.2f}',
            )
        )
        s.add(
            judge.in_range(
                'the goals',
                values,
                *PAN_RANGE,
                "keep the sine's amplitude within the pan servo's ±1.5708 rad",
            )
        )
        torque_criterion(s, 'pan', goals)
        swing = moved(joints)
        s.add(
            Criterion(
                'the pan servo moves',
                swing >= 0.2,
                'the servo does not follow the goals',
                f'it swung {swing:.2f} rad',
            )
        )
    s.stop_student()
    text = 'Ctrl-C disables the pan torque (setTorqueDisable) before the node ends'
    disabled = s.wait(lambda: 'torque disabled' in s.helpers['pan'].output, 2.0)
    s.add(
        Criterion(
            text,
            disabled,
            'catch KeyboardInterrupt and call /olive/servo/pan/setTorqueDisable (on a ROS 2 '
            "install of your own, Jazzy's Ctrl-C handler shuts ROS down first: there use "
            'rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO))',
        )
    )


def check_control_servo_torque_off(s: Session) -> None:
    check_control_servo(s, torque_off_only=True)


def check_pid_testing(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'pid_testing')
    s.expect_endpoint(
        goal_topic('pan'), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic("pan")}'
    )
    s.wait(lambda: len({round(m.data, 2) for _, m in goals}) >= 2, 12.0)
    values = [round(m.data, 2) for _, m in goals]
    s.add(
        Criterion(
            'the goal alternates between 1.57 and 0.0 rad',
            set(values) == {1.57, 0.0},
            'publish 1.57, then 0.0, then 1.57 ... from create_timer(3.0, ...)',
            f'goals {values[:6]}',
        )
    )
    stamps = [t for t, _ in goals]
    period = (stamps[-1] - stamps[0]) / (len(stamps) - 1) if len(stamps) >= 2 else 0.0
    s.add(
        Criterion(
            'a new goal every 3 s',
            2.5 <= period <= 3.5,
            'create_timer(3.0, self.publish_goal)',
            f'every {period:.1f} s' if period else 'fewer than 2 goals',
        )
    )
    torque_criterion(s, 'pan', goals)
    swing = moved(joints)
    s.add(
        Criterion(
            'the pan servo turns to the goals',
            swing >= 1.0,
            'the servo does not follow the goals',
            f'it turned {swing:.2f} rad',
        )
    )
    s.stop_student()


def press(s: Session, process: RosProcess, *events: str) -> bool:
    """Key events ('down left', 'up left') for the node's headless pygame window (owl_gui_hook)."""
    windows = Path(s.temporary.name)
    folders = list(windows.glob('*-*'))
    if not folders:
        return False
    with open(folders[0] / 'keys', 'a') as keys:
        for event in events:
            keys.write(event + '\n')
    return True


def hold_keys(
    s: Session, process: RosProcess, keys: tuple[str, ...], goals: dict[str, list], longest: float = 5.0
) -> float:
    """Hold keys until the goals stop changing (or longest s); return when it started."""
    start = time.monotonic()
    press(s, process, *(f'down {k}' for k in keys))

    def settled() -> bool:
        if time.monotonic() - start < 1.0:
            return False
        recent = [m.data for servo in goals for t, m in goals[servo] if t >= time.monotonic() - 0.5]
        earlier = [
            m.data
            for servo in goals
            for t, m in goals[servo]
            if time.monotonic() - 0.7 <= t < time.monotonic() - 0.5
        ]
        return (
            bool(recent)
            and bool(earlier)
            and max(recent) - min(recent) < 1e-3
            and abs(recent[-1] - earlier[-1]) < 1e-3
        )

    s.wait(settled, longest)
    press(s, process, *(f'up {k}' for k in keys))
    return start


def check_keyboard_servos(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    process = s.student(
        'olive_servo',
        'keyboard_servos',
        env={
            'DISPLAY': None,
            'WAYLAND_DISPLAY': None,
            'OWL_HEADLESS': '1',
            'OWL_WINDOWS_DIR': s.temporary.name,
        },
    )
    for servo in ('pan', 'tilt'):
        s.expect_endpoint(
            goal_topic(servo), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic(servo)}'
        )
    window = s.wait(lambda: press(s, process), START_TIMEOUT)
    if not s.add(
        Criterion(
            'opens a pygame window for the keys',
            window,
            'pygame.display.set_mode(...) gives the window whose keys move the servos',
        )
    ):
        s.stop_student()
        return
    s.wait(lambda: all(len(g) >= 5 for g in goals.values()), 5.0)
    moves = {}
    for keys in (('left', 'up'), ('right', 'down')):
        start = hold_keys(s, process, keys, goals)
        for servo, key in zip(('pan', 'tilt'), keys, strict=True):
            values = [m.data for t, m in goals[servo] if t >= start]
            moves[key] = (values, start)
            range_ = PAN_RANGE if servo == 'pan' else TILT_RANGE
            s.add(judge.bounded_goal(servo, values, *range_, f'{key.title()} is held'))
    for servo, keys in (('pan', ('left', 'right')), ('tilt', ('up', 'down'))):
        first, second = (moves[k][0] for k in keys)
        swing = (max(first + second) - min(first + second)) if first + second else 0.0
        s.add(
            Criterion(
                f'{keys[0].title()}/{keys[1].title()} move the {servo} goal',
                swing >= 0.3,
                f'holding {keys[0].title()} and {keys[1].title()} left the {servo} goal where it was: '
                'read pygame.key.get_pressed() in the timer callback',
                f'it swung {swing:.2f} rad',
            )
        )
    s.stop_student()


def check_imu_control_robot(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('imu', 'pan', 'tilt', imu_command=True)
    hold_imu(s, 0.0, 0.0, 0.0)
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'imu_control_robot')
    s.expect_endpoint(IMU_TOPIC, 'subscriptions', 'sensor_msgs/msg/Imu', f'no subscription on {IMU_TOPIC}')
    for servo in ('pan', 'tilt'):
        s.expect_endpoint(
            goal_topic(servo), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic(servo)}'
        )
    s.wait(lambda: all(len(g) >= 3 for g in goals.values()), 10.0)

    def last(servo: str, since: float) -> float | None:
        values = [m.data for t, m in goals[servo] if t >= since]
        return judge.mean(values[-5:]) if values else None

    results = {}
    for name, (pitch, yaw) in {'yaw': (0.0, 0.6), 'pitch': (0.5, 0.0)}.items():
        start = time.monotonic()
        settle(s, goals['pan'], 0.0, pitch, yaw, lambda m: (m.data,), 1.2)
        results[name] = (last('pan', start + 0.6), last('tilt', start + 0.6))
    pan_yaw, tilt_yaw = results['yaw']
    pan_pitch, tilt_pitch = results['pitch']
    if pan_yaw is None or tilt_yaw is None or pan_pitch is None or tilt_pitch is None:
        s.add(
            Criterion(
                'sends pan and tilt goals while the IMU turns',
                False,
                'publish a goal for each servo from each IMU message (or a timer)',
            )
        )
    else:
        s.add(
            Criterion(
                'the pan goal follows the yaw (turning the IMU left turns the head left)',
                abs(pan_yaw - 0.6) <= 0.15 and abs(pan_pitch) <= 0.15,
                'pan must be the yaw angle and tilt the pitch angle from equations (3); check which '
                'angle goes to which servo and its sign',
                f'pan {pan_yaw:+.2f} rad at yaw +0.60, {pan_pitch:+.2f} rad at pitch +0.50',
            )
        )
        s.add(
            Criterion(
                'the tilt goal follows the pitch (tilting the IMU forward tilts the camera down)',
                abs(tilt_pitch - 0.5) <= 0.15 and abs(tilt_yaw) <= 0.15,
                'tilt must be the pitch angle from equations (3); check which angle goes to which '
                'servo and its sign',
                f'tilt {tilt_pitch:+.2f} rad at pitch +0.50, {tilt_yaw:+.2f} rad at yaw +0.60',
            )
        )
    start = time.monotonic()
    settle(s, goals['pan'], 0.0, 1.4, 2.6, lambda m: (m.data,), 1.5)
    for servo, range_ in (('pan', PAN_RANGE), ('tilt', TILT_RANGE)):
        values = [m.data for t, m in goals[servo] if t >= start]
        s.add(judge.bounded_goal(servo, values, *range_, 'the IMU turns far (yaw 2.6, pitch 1.4 rad)'))
    torque_criterion(s, 'pan', goals['pan'])
    swing = moved(joints)
    s.add(
        Criterion(
            'the pan servo moves with the IMU',
            swing >= 0.3,
            'the servo does not follow the goals',
            f'it turned {swing:.2f} rad',
        )
    )
    s.stop_student()


# -- section 4.5 -------------------------------------------------------------------------------------


def check_display_camera(s: Session) -> None:
    from rclpy.qos import ReliabilityPolicy

    s.kit('camera')
    windows = Path(s.temporary.name)
    s.student(
        'olive_camera',
        'display_camera',
        env={'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1', 'OWL_WINDOWS_DIR': str(windows)},
    )
    info = s.expect_endpoint(
        CAMERA_TOPIC,
        'subscriptions',
        'sensor_msgs/msg/CompressedImage',
        f'no subscription on the camera topic {CAMERA_TOPIC}',
    )
    if info is not None:
        reliable = info.qos_profile.reliability == ReliabilityPolicy.RELIABLE
        s.add(
            Criterion(
                "the subscription's QoS matches the camera's BEST_EFFORT publisher",
                not reliable,
                (
                    'your subscription asks for RELIABLE (the default of a depth 10), but the camera offers '
                    'BEST_EFFORT, so no image ever arrives: subscribe with QoSProfile(depth=10, '
                    'reliability=QoSReliabilityPolicy.BEST_EFFORT, durability=QoSDurabilityPolicy.VOLATILE)'
                ),
                f'reliability {info.qos_profile.reliability.name}',
            )
        )
    matched = info is not None and info.qos_profile.reliability != ReliabilityPolicy.RELIABLE
    shown = matched and s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 10.0)
    s.add(
        Criterion(
            "cv2.imshow shows the camera's images",
            shown,
            (
                'no image reached cv2.imshow in 10 s: convert each message with '
                'CvBridge().compressed_imgmsg_to_cv2(msg) and pass it to cv2.imshow, then cv2.waitKey(1)'
            )
            if matched
            else 'no image can arrive while the QoS does not match',
        )
    )
    s.stop_student()


# -- section 3.4 -------------------------------------------------------------------------------------


def workspace() -> Path:
    return Path(os.environ.get(WORKSPACE_VARIABLE, '.'))


def check_test_package(s: Session) -> None:
    from ament_index_python.packages import PackageNotFoundError, get_package_prefix

    found = ws.packages(workspace()).get('test_package')
    if not s.add(
        Criterion(
            'the workspace has a package named test_package (package.xml)',
            found is not None,
            'in src/: ros2 pkg create test_package --build-type ament_python',
        )
    ):
        return
    assert found is not None
    s.add(
        Criterion(
            'its build type is ament_python (package.xml: <build_type>ament_python</build_type>)',
            found.build_type == 'ament_python',
            f'it is an {found.build_type} package: without --build-type ament_python, ros2 pkg create '
            'makes a CMake package; delete it and create it again with --build-type ament_python',
            found.build_type,
        )
    )
    missing = ws.package_layout_problems(found.path, 'test_package')
    s.add(
        Criterion(
            'it has the layout ros2 pkg create gives: package.xml, setup.py, setup.cfg, '
            'resource/test_package, '
            'test_package/__init__.py',
            not missing,
            'create the package with ros2 pkg create rather than by hand, or add what is missing',
            '; '.join(missing),
        )
    )
    try:
        prefix = Path(get_package_prefix('test_package')).resolve()
    except PackageNotFoundError:
        prefix = None
    s.add(
        Criterion(
            'colcon build installs it: ros2 pkg list lists test_package',
            prefix is not None and workspace().resolve() in prefix.parents,
            'run colcon build --symlink-install in the workspace root, then source install/setup.bash',
            str(prefix or 'not installed'),
        )
    )


# -- section 3.6 exercise: currency or factorial ----------------------------------------------------

# Services every node offers (parameters, type description), never the exercise's own.
STANDARD_SERVICE_SUFFIXES = (
    '/describe_parameters',
    '/get_parameter_types',
    '/get_parameters',
    '/list_parameters',
    '/set_parameters',
    '/set_parameters_atomically',
    '/get_type_description',
)
REFERENCE = {
    'currency': (
        "the reference solution's currency_server offers currency_conversion "
        '(olive_interfaces/srv/CurrencyConv: float64 euros -> float64 dollars, pounds, swiss_francs)'
    ),
    'factorial': (
        "the reference solution's factorial_server offers factorial "
        '(olive_interfaces/srv/Factorial: int64 n -> uint64 factorial)'
    ),
}
FLOAT_TYPES = ('double', 'float')
INTEGER_TYPES = ('int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'int64', 'uint64')


def own_service(name: str) -> bool:
    return not name.endswith(STANDARD_SERVICE_SUFFIXES) and '/_action/' not in name


def fields(message: Any, kinds: tuple[str, ...]) -> list[str]:
    return [name for name, kind in message.get_fields_and_field_types().items() if kind in kinds]


def find_student_executable(s: Session, subject: str, role: str) -> tuple[str, str] | None:
    """(package, executable) of the workspace for the exercise, olive_srvcli (the course's) first."""
    names = sorted(ws.packages(workspace()), key=lambda name: name != 'olive_srvcli')
    for package in names:
        executable = ws.find_executable(ws.executables(workspace(), package), subject, role)
        if executable:
            return package, executable
    s.add(
        Criterion(
            f'the workspace has a {subject} {role} executable',
            False,
            f"no executable with '{subject}' and '{role}' in its name in the workspace's packages "
            f'({REFERENCE[subject]}; its executable is {subject}_{role})',
        )
    )
    return None


def check_service_server(s: Session, subject: str) -> None:
    found = find_student_executable(s, subject, 'server')
    if found is None:
        return
    s.student(*found)

    def services() -> list[tuple[str, str]]:
        return [
            (name, types[0])
            for name, types in s.node.get_service_names_and_types()
            if own_service(name) and types and not name.startswith(f'/{PROBE_NODE}/')
        ]

    s.wait(lambda: bool(services()), START_TIMEOUT)
    offered = sorted(services(), key=lambda item: subject[:4] not in (item[0] + item[1]).lower())
    if not s.add(
        Criterion(
            f'{found[1]} offers a service',
            bool(offered),
            f'no service appeared: create_service(YourType, name, callback) ({REFERENCE[subject]})',
            ', '.join(f'{name} ({kind})' for name, kind in offered),
        )
    ):
        s.stop_student()
        return
    name, type_name = offered[0]
    srv = get_service(type_name)  # the student's workspace is sourced: its types import
    number_fields = fields(srv.Request(), FLOAT_TYPES + INTEGER_TYPES)
    if not s.add(
        Criterion(
            f"{type_name}'s request has a number field",
            bool(number_fields),
            f'the request must carry the {"euros" if subject == "currency" else "integer"} '
            f'({REFERENCE[subject]})',
            ', '.join(srv.Request().get_fields_and_field_types()),
        )
    ):
        s.stop_student()
        return
    field = number_fields[0]
    integer = srv.Request().get_fields_and_field_types()[field] in INTEGER_TYPES

    def ask(value: float) -> Any | None:
        request = srv.Request()
        setattr(request, field, int(value) if integer else float(value))
        response = s.call(srv, name, request)
        if response is None:
            s.add(
                Criterion(
                    f'{name} answers {value:g}',
                    False,
                    'no answer in 10 s: the callback must return the response',
                )
            )
        return response

    if subject == 'currency':
        answers = {euros: ask(euros) for euros in (100, 250)}
        if None not in answers.values():
            amounts = {
                euros: [float(getattr(r, f)) for f in fields(r, FLOAT_TYPES + INTEGER_TYPES)]
                for euros, r in answers.items()
            }
            for criterion in judge.currency_answers(amounts[100], amounts[250]):
                s.add(criterion)
    else:
        for n in (5, 0, 10):
            response = ask(n)
            if response is not None:
                values = [getattr(response, f) for f in fields(response, FLOAT_TYPES + INTEGER_TYPES)]
                s.add(judge.factorial_answer(n, values))
    s.stop_student()


def check_currency_server(s: Session) -> None:
    check_service_server(s, 'currency')


def check_factorial_server(s: Session) -> None:
    check_service_server(s, 'factorial')


CLIENT_ARGUMENT = {'currency': 100, 'factorial': 5}
RATES = (1.25, 0.75, 1.5)  # the check's own server: different units per euro for each field


def check_service_client(s: Session, subject: str) -> None:
    found = find_student_executable(s, subject, 'client')
    if found is None:
        return
    argument = CLIENT_ARGUMENT[subject]
    process = s.student(*found, str(argument))

    def clients() -> list[tuple[str, str]]:
        found_clients = []
        for node, namespace in s.node.get_node_names_and_namespaces():
            if node == PROBE_NODE or node.startswith(('olive_', '_')):
                continue
            try:
                pairs = s.node.get_client_names_and_types_by_node(node, namespace)
            except Exception:  # the node left the graph between the two calls
                continue
            found_clients += [(name, types[0]) for name, types in pairs if own_service(name) and types]
        return found_clients

    s.wait(lambda: bool(clients()), START_TIMEOUT)
    seen = clients()
    if not s.add(
        Criterion(
            f'{found[1]} {argument} creates a service client',
            bool(seen),
            f'no client appeared: create_client(YourType, name) ({REFERENCE[subject]})',
            ', '.join(f'{name} ({kind})' for name, kind in seen),
        )
    ):
        if process.running():
            s.stop_student()
        return
    name, type_name = seen[0]
    srv = get_service(type_name)  # the student's workspace is sourced: its types import
    requests: list[float] = []
    expected: list[float] = []

    def answer(request: Any, response: Any) -> Any:
        numbers = fields(request, FLOAT_TYPES + INTEGER_TYPES)
        value = getattr(request, numbers[0]) if numbers else 0
        requests.append(value)
        for flag in fields(response, ('boolean',)):
            setattr(response, flag, True)
        outputs = fields(response, FLOAT_TYPES + INTEGER_TYPES)
        expected.clear()
        for index, out in enumerate(outputs):
            kind = response.get_fields_and_field_types()[out]
            if subject == 'currency':
                result = round(value * RATES[index % len(RATES)], 2)
            else:
                result = math.factorial(int(value)) if 0 <= value <= 20 else 0
            result = int(result) if kind in INTEGER_TYPES else float(result)
            setattr(response, out, result)
            expected.append(result)
        return response

    s.node.create_service(srv, name, answer)
    s.wait(lambda: not process.running(), 15.0)
    s.add(
        Criterion(
            f'sends the command-line value ({found[1]} {argument} asks for {argument})',
            any(math.isclose(r, argument) for r in requests),
            'read the value from sys.argv[1] and put it into the request',
            f'requests {requests}',
        )
    )
    printed = judge.numbers_in(process.output)
    s.add(
        Criterion(
            f"prints the server's answer ({', '.join(f'{v:g}' for v in expected) or 'nothing asked'})",
            bool(expected) and all(any(math.isclose(v, p, abs_tol=0.006) for p in printed) for v in expected),
            "log the response's fields with self.get_logger().info(...)",
            judge.tail_lines(process.output, 1),
        )
    )
    client_ended(s, process)


def check_currency_client(s: Session) -> None:
    check_service_client(s, 'currency')


def check_factorial_client(s: Session) -> None:
    check_service_client(s, 'factorial')


# -- section 3.7.1: a parameter file ----------------------------------------------------------------

# The nodes a parameter file of the course sets, with the defaults an edited file must change.
PARAMETER_FILE_NODES = {
    'turtlesim': (
        ('turtlesim', 'turtlesim_node'),
        {'background_r': 69, 'background_g': 86, 'background_b': 255},
    ),
    'random_number_publisher': (
        ('random_number_ps', 'random_number_publisher'),
        {'upper_limit': 100},
    ),
}


def check_params_file(s: Session) -> None:
    files = ws.parameter_files(workspace(), Path.home())
    files.sort(key=lambda f: f.name != 'turtlesim.yaml')
    if not s.add(
        Criterion(
            'a parameter file is found (in the workspace or ~/Documents)',
            bool(files),
            'save one as section 3.7.1 does: cd ~/Documents; ros2 param dump /turtlesim > turtlesim.yaml',
            ', '.join(str(f) for f in files[:3]),
        )
    ):
        return
    chosen, nodes, problem = files[0], {}, ''
    for candidate in files:
        try:
            nodes = ws.read_parameter_file(candidate.read_text(errors='replace'))
        except ValueError as error:
            problem = problem or f'{candidate.name}: {error}'
            continue
        if any(key.strip('/') in PARAMETER_FILE_NODES for key in nodes):
            chosen = candidate
            break
    target = next((key for key in nodes if key.strip('/') in PARAMETER_FILE_NODES), None)
    if not s.add(
        Criterion(
            f"{chosen.name} sets a node's ros__parameters (turtlesim or random_number_publisher)",
            target is not None,
            problem
            or 'the file must start with the node name, then ros__parameters:, as ros2 param dump '
            '/turtlesim writes it',
            ', '.join(nodes) or str(chosen),
        )
    ):
        return
    assert target is not None
    node = target.strip('/')
    (package, executable), defaults = PARAMETER_FILE_NODES[node]
    values = {
        name: value
        for name, value in nodes[target].items()
        if not name.startswith(('qos_overrides.', 'use_sim_time', 'start_type_description_service'))
    }
    changed = {name: value for name, value in values.items() if name in defaults and value != defaults[name]}
    s.add(
        Criterion(
            'the file changes a value from its default, as the course asks (e.g. background 0/0/0)',
            bool(changed),
            f"a fresh dump holds the defaults ({', '.join(f'{k} {v}' for k, v in defaults.items())}): "
            'edit the values in the file to see the difference',
            ', '.join(f'{k} {v}' for k, v in values.items()),
        )
    )
    env: dict[str, str | None] = {'DISPLAY': None, 'WAYLAND_DISPLAY': None}
    process = s.sandbox.command(
        ['ros2', 'run', package, executable, '--ros-args', '--params-file', str(chosen)],
        label=executable,
        env=env,
    )
    s.wait(lambda: node in s.node.get_node_names() or not process.running(), START_TIMEOUT)
    actual = s.get_parameters(node, list(values)) if process.running() else {}
    different = {name: actual.get(name) for name, value in values.items() if actual.get(name) != value}
    s.add(
        Criterion(
            f'ros2 run {package} {executable} --ros-args --params-file {chosen.name} starts it with '
            "the file's values",
            process.running() and not different,
            (
                f'the node has {", ".join(f"{k} {v!r}" for k, v in different.items())}: '
                f"the file's first key must be the node's name (/{node}) and its values of the "
                "parameters' types"
            )
            if process.running()
            else f'it did not start with the file: {judge.tail_lines(process.output, 2)}',
            ', '.join(f'{k} {actual.get(k)!r}' for k in values),
        )
    )
    process.stop(3.0)


# -- 4.3.2 +: the IMU topic parameter ---------------------------------------------------------------

OTHER_IMU_TOPIC = '/owl_check/imu'


def feed_imu(s: Session, topic: str, pitch: float, seconds: float) -> None:
    """Publish the IMU's messages ourselves on a topic of our choice, 20 per second."""
    from owl_common.quaternion import from_euler
    from sensor_msgs.msg import Imu

    publisher = s.node.create_publisher(Imu, topic, 10)
    message = Imu()
    message.header.frame_id = 'imu'
    x, y, z, w = from_euler(0.0, pitch, 0.0)
    message.orientation.x, message.orientation.y, message.orientation.z, message.orientation.w = x, y, z, w
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        publisher.publish(message)
        time.sleep(0.05)


def check_imu_turtle_topic(s: Session) -> None:
    from geometry_msgs.msg import Twist

    process = s.student('olive_imu', 'imu_turtle')
    s.wait(lambda: 'imu_turtle' in s.node.get_node_names(), START_TIMEOUT)
    names = [name for name, value in s.own_parameters('imu_turtle').items() if value == IMU_TOPIC]
    s.stopped = True  # our own stop: its exit is no crash
    process.stop(3.0)
    if not s.add(
        Criterion(
            f"a string parameter of imu_turtle holds the IMU's topic (default {IMU_TOPIC})",
            bool(names),
            f"declare_parameter('imu_topic', '{IMU_TOPIC}') and subscribe to "
            "self.get_parameter('imu_topic').value",
            ', '.join(names),
        )
    ):
        return
    s.wait(lambda: 'imu_turtle' not in s.node.get_node_names(), 3.0)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle', '--ros-args', '-p', f'{names[0]}:={OTHER_IMU_TOPIC}')
    s.stopped = False
    s.expect_endpoint(
        OTHER_IMU_TOPIC,
        'subscriptions',
        'sensor_msgs/msg/Imu',
        f'with -p {names[0]}:={OTHER_IMU_TOPIC} nothing subscribes there: create the subscription with '
        'the parameter\'s value',
    )
    old = s.endpoints(IMU_TOPIC, 'subscriptions')
    s.add(
        Criterion(
            f'it no longer subscribes to {IMU_TOPIC}',
            not old,
            'the subscription still uses the fixed topic: use the parameter\'s value instead',
        )
    )
    start = time.monotonic()
    feed_imu(s, OTHER_IMU_TOPIC, 0.4, 2.0)
    speeds = [m.linear.x for t, m in twists if t >= start + 1.0]
    s.add(
        Criterion(
            f'the IMU on {OTHER_IMU_TOPIC} (pitched 0.4 rad) drives the turtle forward',
            judge.mean(speeds) > judge.STILL,
            'no forward velocity from the IMU on the new topic',
            f'linear.x {judge.mean(speeds):+.2f} from {len(speeds)} messages',
        )
    )
    s.stop_student()


# -- 4.4 + and 4.4.1 +: frequency, torque and speed extras ------------------------------------------


def numeric_parameters(s: Session, node: str, preferred: tuple[str, ...]) -> list[tuple[str, float]]:
    """(name, value) of a node's own numeric parameters, those naming a preferred word first."""
    found = [
        (name, value)
        for name, value in s.own_parameters(node).items()
        if isinstance(value, (int, float)) and not isinstance(value, bool)
    ]
    return sorted(found, key=lambda item: not any(word in item[0].lower() for word in preferred))


def scaled(value: float, factor: float) -> float:
    if isinstance(value, int):
        return max(1, round(value * factor)) if value else 1
    return value * factor if value else 1.0


def check_control_servo_frequency(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    s.student('olive_servo', 'control_servo')
    s.wait(lambda: len(goals) >= 20 and 'control_servo' in s.node.get_node_names(), START_TIMEOUT)

    def measured_rate() -> float:
        start = time.monotonic() + 0.3  # the new period takes effect from the timer's next call
        s.wait(lambda: time.monotonic() > start + 1.2, 2.0)
        return judge.rate([t for t, _ in goals if t >= start])

    before = measured_rate()
    found, detail = None, []
    for name, value in numeric_parameters(s, 'control_servo', ('freq', 'rate', 'period', 'hz')):
        changed = scaled(value, 0.5)
        ok, _ = s.set_parameter('control_servo', name, changed)
        if not ok:
            continue
        after = measured_rate()
        s.set_parameter('control_servo', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.0f}->{after:.0f} goals/s')
        if before > 0 and abs(after - before) > 0.3 * before:
            found = name
            break
        before = measured_rate()
    s.add(
        Criterion(
            'a parameter changes the publishing frequency while it runs (ros2 param set)',
            found is not None,
            "declare_parameter('frequency', 100.0) and change the timer's period when it is set "
            '(add_post_set_parameters_callback), or read it when the timer is created',
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()


KEYBOARD_ENV_KEYS = ('DISPLAY', 'WAYLAND_DISPLAY')


def start_keyboard_servos(s: Session) -> RosProcess:
    env: dict[str, str | None] = {key: None for key in KEYBOARD_ENV_KEYS}
    env.update({'OWL_HEADLESS': '1', 'OWL_WINDOWS_DIR': s.temporary.name})
    return s.student('olive_servo', 'keyboard_servos', env=env)


def check_keyboard_servos_torque(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    start_keyboard_servos(s)
    s.wait(lambda: all(len(g) >= 5 for g in goals.values()), START_TIMEOUT)
    for servo in ('pan', 'tilt'):
        torque_criterion(s, servo, goals[servo])
    s.stop_student()
    disabled = s.wait(lambda: all('torque disabled' in s.helpers[v].output for v in ('pan', 'tilt')), 2.0)
    s.add(
        Criterion(
            'Ctrl-C disables the pan and tilt torque (setTorqueDisable) before the node ends',
            disabled,
            'after rclpy.spin, call /olive/servo/pan/setTorqueDisable and '
            '/olive/servo/tilt/setTorqueDisable; '
            "(on a ROS 2 install of your own, Jazzy's Ctrl-C handler shuts ROS down first: there use "
            'rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO))',
            ', '.join(v for v in ('pan', 'tilt') if 'torque disabled' in s.helpers[v].output),
        )
    )


def check_keyboard_servos_speed(s: Session) -> None:
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    pan = s.collect(Float32, goal_topic('pan'))
    process = start_keyboard_servos(s)
    window = s.wait(lambda: press(s, process) and len(pan) >= 5, START_TIMEOUT)
    if not s.add(
        Criterion(
            'opens a pygame window and publishes pan goals',
            window,
            'pygame.display.set_mode(...) gives the window whose keys move the servos',
        )
    ):
        s.stop_student()
        return
    keys = itertools.cycle(('left', 'right'))

    def speed() -> float:
        key = next(keys)
        start = time.monotonic()
        press(s, process, f'down {key}')
        s.wait(lambda: time.monotonic() > start + 0.7, 1.0)
        press(s, process, f'up {key}')
        samples = [(t, m.data) for t, m in pan if start + 0.2 <= t <= start + 0.7]
        return judge.slope([(t, v) for t, v in samples if PAN_RANGE[0] + 0.01 < v < PAN_RANGE[1] - 0.01])

    before = speed()
    found, detail = None, []
    for name, value in numeric_parameters(s, 'keyboard_servos', ('speed', 'step', 'vel', 'rate', 'gain')):
        if any(word in name.lower() for word in ('min', 'max', 'limit', 'bound')):
            continue  # the goals' bounds, not their speed
        changed = scaled(value, 2.0)
        ok, _ = s.set_parameter('keyboard_servos', name, changed)
        if not ok:
            continue
        after = speed()
        s.set_parameter('keyboard_servos', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.2f}->{after:.2f} rad/s')
        if before > judge.STILL and abs(after - before) > 0.3 * before:
            found = name
            break
        before = speed()
    s.add(
        Criterion(
            'a parameter changes how fast a held key moves the servo (ros2 param set)',
            found is not None,
            "declare_parameter('speed', 1.0) and scale each step of the goal by "
            "self.get_parameter('speed').value in the timer callback",
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()


# -- 4.5 +: the robot_camera launch file ------------------------------------------------------------


def check_robot_camera_launch(s: Session) -> None:
    from std_msgs.msg import Float32

    files = [
        f
        for f in launch_files('olive_camera')
        if 'imu_control_robot' in f.read_text() and 'display_camera' in f.read_text()
    ]
    if not s.add(
        Criterion(
            'olive_camera installs a launch file that names imu_control_robot and display_camera',
            bool(files),
            'a launch file in olive_camera/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files),
        )
    ):
        return
    s.kit('imu', 'pan', 'tilt', 'camera')  # the IMU's scripted motion turns the head
    pan = s.collect(Float32, goal_topic('pan'))
    windows = Path(s.temporary.name)
    s.student_launch(
        'olive_camera',
        files[0].name,
        env={'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1', 'OWL_WINDOWS_DIR': str(windows)},
    )
    s.wait(lambda: len({round(m.data, 2) for _, m in pan}) >= 3, 20.0)
    s.add(
        Criterion(
            f'ros2 launch olive_camera {files[0].name}: imu_control_robot turns the head with the IMU',
            len({round(m.data, 2) for _, m in pan}) >= 3,
            'no changing pan goals arrived: the launch file must start olive_servo\'s imu_control_robot',
            f'{len(pan)} pan goals',
        )
    )
    shown = s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 15.0)
    s.add(
        Criterion(
            "ros2 launch ... : display_camera shows the camera's images",
            shown,
            "no image reached cv2.imshow: the launch file must start olive_camera's display_camera",
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)


CHECKS: dict[str, Callable[[Session], None]] = {
    'test_package': check_test_package,
    'currency_server': check_currency_server,
    'currency_client': check_currency_client,
    'factorial_server': check_factorial_server,
    'factorial_client': check_factorial_client,
    'params_file': check_params_file,
    'imu_turtle_topic': check_imu_turtle_topic,
    'control_servo_frequency': check_control_servo_frequency,
    'keyboard_servos_torque': check_keyboard_servos_torque,
    'keyboard_servos_speed': check_keyboard_servos_speed,
    'robot_camera_launch': check_robot_camera_launch,
    'random_number_publisher': check_random_number_publisher,
    'random_number_subscriber': check_random_number_subscriber,
    'counter_publisher': check_counter_publisher,
    'turtle_random_velocity': check_turtle_random_velocity,
    'temp_server': check_temp_server,
    'temp_client': check_temp_client,
    'upper_limit': check_upper_limit,
    'lower_limit': check_lower_limit,
    'turtle_launch': check_turtle_launch,
    'imu_turtle': check_imu_turtle,
    'imu_turtle_launch': check_imu_turtle_launch,
    'imu_turtle_speed': check_imu_turtle_speed,
    'pid_testing': check_pid_testing,
    'control_servo': check_control_servo,
    'control_servo_torque_off': check_control_servo_torque_off,
    'keyboard_servos': check_keyboard_servos,
    'imu_control_robot': check_imu_control_robot,
    'display_camera': check_display_camera,
}


def run(exercise_id: str) -> int:
    session = Session()
    stop = {'signal': False}

    def on_term(signum: int, frame: object) -> None:
        # owl check's hard time limit: clean up (finally below) instead of leaving the nodes behind.
        stop['signal'] = True
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, on_term)
    try:
        CHECKS[exercise_id](session)
    except Failed:
        pass
    except KeyboardInterrupt:
        if not stop['signal']:
            raise
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        session.close()
    return 0


def main() -> int:
    if len(sys.argv) != 2 or sys.argv[1] not in CHECKS:
        print(f'usage: python -m owl_cli.check_ros {{{",".join(CHECKS)}}}', file=sys.stderr)
        return 2
    return run(sys.argv[1])


if __name__ == '__main__':
    sys.exit(main())
