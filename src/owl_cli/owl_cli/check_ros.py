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
from typing import Any

# Discovery stays on this machine whatever the student's shell says (set before rclpy starts).
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from owl_common.probe import Probe
from owl_common.processes import RosProcess, RosSandbox
from rcl_interfaces.srv import GetParameters, ListParameters, SetParameters
from rclpy.parameter import Parameter, parameter_value_to_python

from owl_cli import check_criteria as judge
from owl_cli.check_report import RESULT_PREFIX, Criterion

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
                    label=f'servo {servo}',
                )
                self.helpers[servo] = process
                nodes.append(f'olive_servo_{servo}_dcm_srv')
        if 'camera' in modules:
            self.helper('olive_sim', 'camera_sim')
            nodes.append('olive_camera_eye_dcm_srv')
        for name in nodes:
            if not self.wait(lambda n=name: n in self.node.get_node_names(), 30.0):
                raise RuntimeError(f'the simulated kit did not start ({name})')

    def student(self, package: str, executable: str, *args: str, env: dict | None = None) -> RosProcess:
        """`ros2 run package executable args` from the student's workspace."""
        self.student_process = self.sandbox.command(
            ['ros2', 'run', package, executable, *args], label=executable, env=env
        )
        return self.student_process

    def student_launch(self, package: str, launch_file: str) -> RosProcess:
        self.student_process = self.sandbox.command(
            ['ros2', 'launch', package, launch_file], label=launch_file
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
                    'try/except (KeyboardInterrupt, ExternalShutdownException); last lines: '
                    f'{judge.tail_lines(process.output)}'
                ),
                f'exit code {code}',
            )
        )

    def close(self) -> None:
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

    def endpoints(self, topic: str, kind: str) -> list[Any]:
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
    ) -> Any | None:
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

    def collect(self, msg_type: Any, topic: str, qos: Any = 10) -> list[tuple[float, Any]]:
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
        response = self.call(GetParameters, f'/{node}/get_parameters', GetParameters.Request(names=[name]))
        return parameter_value_to_python(response.values[0]) if response and response.values else None

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

    s.student('random_number_ps', 'random_number_subscriber')
    s.expect_endpoint(
        '/random_numbers',
        'subscriptions',
        'std_msgs/msg/Int32',
        "no subscription on random_numbers: create_subscription(Int32, 'random_numbers', callback, 10)",
    )
    publisher = s.node.create_publisher(Int32, '/random_numbers', 10)
    sent = (17, 42, 93)

    def printed() -> bool:
        words = set(s.student_process.output.replace(':', ' ').split())
        return all(str(n) in words for n in sent)

    deadline = time.monotonic() + 10.0
    while not printed() and time.monotonic() < deadline and s.student_process.running():
        for number in sent:
            publisher.publish(Int32(data=number))
        time.sleep(0.5)
    s.add(
        Criterion(
            'prints every number it receives (17, 42, 93 were published)',
            printed(),
            "log each message in the callback: self.get_logger().info(f'Received: {msg.data}')",
            judge.tail_lines(s.student_process.output, 2),
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
    ):
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
    for name in s.parameters('imu_turtle'):
        value = s.get_parameter('imu_turtle', name)
        if (
            name.startswith(STANDARD_PARAMETERS)
            or isinstance(value, bool)
            or not isinstance(value, (int, float))
        ):
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
    from olive_sim.quaternion import from_euler

    x, y, z, w = from_euler(roll, pitch, yaw)
    publisher = getattr(s, '_imu_command', None)
    if publisher is None:
        publisher = s._imu_command = s.node.create_publisher(Quaternion, IMU_COMMAND_TOPIC, 10)
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
            'catch KeyboardInterrupt and call /olive/servo/pan/setTorqueDisable; with '
            "rclpy's own Ctrl-C handler ROS is already shut down by then: "
            'rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)',
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
    if None in (pan_yaw, tilt_yaw, pan_pitch, tilt_pitch):
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


CHECKS: dict[str, Callable[[Session], None]] = {
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
