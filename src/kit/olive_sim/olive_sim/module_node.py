"""What every simulated Olive module shares: names, status, temperature, button, LED.

A module of type T with namespace N publishes under olive_kit.description.topic(T, N, ...) (the
course's naming) from a node named olive_T_N_dcm_srv (like the course's /olive_servo_pan_dcm_srv).
"""

from __future__ import annotations

import math
import os
import re
import signal
import sys
import threading
import time
from collections.abc import Callable
from typing import Any, ClassVar

import yaml
from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from olive_kit.description import WEB_PORT, node_name, topic
from owl_common.periodic import PeriodicThread, wall_time_ns
from owl_common.polled_subscription import PolledSubscription
from owl_common.quaternion import Quaternion
from owl_common.run import spin_node
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from rclpy.clock import ROSClock
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile
from sensor_msgs.msg import Temperature
from std_msgs.msg import Bool

from olive_sim import network_settings
from olive_sim.module_log import LogBook, RecordingLogger
from olive_sim.process_stats import TrafficMeter
from olive_sim.restart import start_again, take_handover

FIRMWARE_VERSION = 'olive_sim 0.1.0'
NAMESPACE_PATTERN = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')
STATUS_PERIOD = 1.0  # s: status, temperature and switch are published at 1 Hz
# s: how late a sensor's samples (IMU, servo joint) may be made up after the machine held the
# module up, as a real module's own processor would have sent them (PeriodicThread's catch_up).
# Suite runs on two busy cores held modules up 0.21, 0.24 and 0.33 s (as turtlesim's tick, 0.5 s).
SENSOR_CATCH_UP = 0.5
WARN_EVERY = 2.0     # s between repeats of one kind of warning


def check_namespace(namespace: str) -> str:
    """The namespace if it can be one ROS name token, else ValueError with the reason."""
    if not NAMESPACE_PATTERN.match(namespace):
        raise ValueError(f"namespace '{namespace}' is not valid: use letters, digits and '_', "
                         'starting with a letter')
    return namespace


def read_namespace(default: str, args: list[str]) -> str:
    """The `namespace` parameter given on the command line (args as in sys.argv), else default.

    The node's name contains the namespace, so it has to be known before the node is created. It
    is read from the arguments, not through a short-lived node: destroying a node right after
    creating it raced Fast DDS's own threads (a segfault in about 1 of 30 kit launches). Like
    rclpy, later arguments win; parameter files count with their entries for all nodes (/**).
    """
    value: Any = default
    in_ros_args = False
    tokens = iter(args)
    for token in tokens:
        if token in ('--ros-args', '--'):
            in_ros_args = token == '--ros-args'
        elif in_ros_args and token in ('-p', '--param'):
            name, _, text = next(tokens, '').partition(':=')
            if name == 'namespace':
                value = yaml.safe_load(text)
        elif in_ros_args and token == '--params-file':
            value = _params_file_namespace(next(tokens, ''), value)
    if not isinstance(value, str):
        raise ValueError(f'parameter namespace must be a string, got {value!r}')
    return check_namespace(value)


def _params_file_namespace(path: str, current: Any) -> Any:
    try:
        with open(path, encoding='utf-8') as stream:
            content = yaml.safe_load(stream)
    except (OSError, yaml.YAMLError) as error:
        raise ValueError(f'cannot read parameter file {path!r}: {error}') from None
    for_all_nodes = content.get('/**', {}) if isinstance(content, dict) else {}
    parameters = for_all_nodes.get('ros__parameters', {}) if isinstance(for_all_nodes, dict) else {}
    return parameters.get('namespace', current) if isinstance(parameters, dict) else current


def describe(description: str, read_only: bool = False, **ranges: Any) -> ParameterDescriptor:
    """A parameter descriptor; ranges are FloatingPointRange/IntegerRange objects by keyword."""
    return ParameterDescriptor(description=description, read_only=read_only, **ranges)


class OliveModule(Node):
    """Base class of the module nodes: common topics, the `namespace` parameter, web page, restart."""

    # What the process before this one handed over at a restart (restart.py); run_module sets it.
    handover: ClassVar[dict[str, Any]] = {}

    def __init__(self, module_type: str, namespace: str, serial: str) -> None:
        self.logbook = LogBook()
        super().__init__(node_name(module_type, namespace))
        self._recording_logger = RecordingLogger(super().get_logger(), self.logbook)
        self.traffic = TrafficMeter()
        self.firmware = FIRMWARE_VERSION
        self.boot_id = time.time_ns()  # tells a page that the module started again
        self.page: Any = None  # the ModulePage, once start_page() serves it
        self.restart_delay: float | None = None  # set by the page's Restart Services / Reboot Device
        self.module_type = module_type
        self.namespace_name = namespace
        self.serial = serial
        self.declare_parameter('namespace', namespace, describe(
            f"Module namespace: topics are {topic(module_type, '<namespace>', '...')}", read_only=True))
        self.declare_parameter('button_pressed', False, describe(
            'Simulated state of the module button, published on switch.'))
        self.declare_parameter('address', network_settings.FACTORY_ADDRESS, describe(
            "The module's IP address at start (its web page answers at 127.B.C.D for A.B.C.D; the "
            "page's Network Settings change it).", read_only=True))
        self.declare_parameter('web_port', WEB_PORT, describe(
            'TCP port of the web page (0: no page).', read_only=True,
            integer_range=[IntegerRange(from_value=0, to_value=65535, step=1)]))
        self.led_on = False
        self.started = time.monotonic()
        self._wrong_led_types: set[str] = set()
        self._last_warning: dict[str, float] = {}
        self._periodic: list[PeriodicThread] = []
        self._polled: list[PolledSubscription] = []
        self.status_publisher = self.create_publisher(DiagnosticStatus, self.topic('status'), 10)
        self.temperature_publisher = self.create_publisher(Temperature, self.topic('temperature'), 10)
        self.switch_publisher = self.create_publisher(Bool, self.topic('switch'), 10)
        self.led_subscription = self.create_subscription(Bool, self.topic('led'), self._on_led, 10)
        self.add_post_set_parameters_callback(self._publish_button_change)
        self.status_timer = self.create_timer(STATUS_PERIOD, self._publish_status)

    def topic(self, name: str) -> str:
        """The absolute name of the module's topic `name` (olive_kit.description.topic)."""
        return topic(self.module_type, self.namespace_name, name)

    def get_logger(self) -> Any:
        """The node's logger; what it logs also goes to the page's Log Monitor."""
        recording = getattr(self, '_recording_logger', None)
        return recording if recording is not None else super().get_logger()

    # -- the web page and restarts ----------------------------------------------------------

    def start_page(self) -> None:
        """Serve the module's page at its address (one warning line if that cannot be done)."""
        port = self.get_parameter('web_port').value
        network = self.handover.get('network')
        try:
            settings = (network_settings.checked(network_settings.NetworkSettings(**network))
                        if isinstance(network, dict) else
                        network_settings.default_settings(self.get_parameter('address').value))
        except (TypeError, ValueError) as error:
            raise ValueError(f'parameter address: {error}') from None
        if port == 0:
            return
        from olive_sim.module_page import ModulePage  # aiohttp (0.2 s of CPU) only for a page

        page = ModulePage(self, settings, port)
        try:
            page.start()
        except OSError as error:
            self.get_logger().warning(
                f'no web page: {page.url} cannot be served ({error.strerror or error}; another module '
                f'with the address {settings.address}?)')
            return
        except ValueError as error:  # the environment's OWL_TRUSTED_ORIGINS
            self.get_logger().warning(f'no web page: {error}')
            return
        self.page = page
        door = f'; through the front door: {page.address}' if page.address != page.url else ''
        self.get_logger().info(f'web page at {page.url} (module address {settings.address}){door}')

    def request_restart(self, delay: float, after: float) -> None:
        """Stop as at Ctrl-C in `after` s, then start again (run_module) after `delay` s."""
        self.restart_delay = delay
        threading.Timer(after, os.kill, (os.getpid(), signal.SIGTERM)).start()

    def handover_state(self) -> dict[str, Any]:
        """What the next process of this module keeps (extended by modules with physical state)."""
        return {'network': self.page.settings.as_dict()} if self.page is not None else {}

    def imu_orientation(self) -> Quaternion | None:
        """The orientation the module's IMU last published, for the Debug GUI (None: no IMU)."""
        return None

    def now_ns(self) -> int:
        """The node's ROS time in ns, for stamps.

        Clock.now() costs as much as a publication, so the system clock (which ROS time is without sim
        time) is read directly when it is the same.
        """
        clock = self.get_clock()
        if isinstance(clock, ROSClock) and clock.ros_time_is_active:  # a node's clock is a ROSClock
            return clock.now().nanoseconds
        return time.time_ns()

    def ros_time_at(self, monotonic: float) -> int:
        """The node's ROS time in ns at an instant given as time.monotonic() (a sample's due time)."""
        clock = self.get_clock()
        if isinstance(clock, ROSClock) and clock.ros_time_is_active:
            return clock.now().nanoseconds - round((time.monotonic() - monotonic) * 1e9)
        return wall_time_ns(monotonic)

    def create_polled_subscription(self, msg_type: type, topic: str, callback: Callable[[Any], None],
                                   qos: QoSProfile | int, raw: bool = False) -> PolledSubscription:
        """A subscription the executor never wakes up for: see PolledSubscription."""
        subscription = PolledSubscription(self, msg_type, topic, callback, qos, raw)
        self._polled.append(subscription)
        return subscription

    def create_periodic(self, rate: float, callback: Callable[[], None], name: str,
                        catch_up: float = 0.0) -> PeriodicThread:
        """Run callback at rate Hz on a thread of its own until the node is destroyed.

        catch_up: see PeriodicThread. A sensor that makes up its samples says so when the machine
        held it up too long to make them up: its stamps then have a gap a real module's would not.
        """
        def skipped(count: int, jump: float) -> None:
            self.warn(f'{name} skipped', f'{name}: the machine held this module up {jump:.2f} s, longer '
                      f'than the {catch_up} s it makes up; {count} samples skipped')

        periodic = PeriodicThread(rate, callback, f'{self.get_name()}.{name}', self.context.ok,
                                  catch_up=catch_up, skipped=skipped if catch_up > 0 else None)
        self._periodic.append(periodic)
        return periodic

    def destroy_node(self) -> None:
        """Stop the page and the periodic threads, then destroy the node as rclpy does."""
        # spin_node already ignores a second Ctrl-C during this clean-up.
        if self.page is not None:
            self.page.stop()
        for periodic in self._periodic:
            periodic.stop()
        for subscription in self._polled:
            subscription.destroy()
        super().destroy_node()

    # -- to be refined by each module -------------------------------------------------------

    def temperature(self) -> float:
        """Board temperature in deg C."""
        return 35.0

    def status_values(self) -> dict[str, str]:
        """Module-specific key/values for the status message."""
        return {}

    def status_level(self) -> tuple[bytes, str]:
        """The status message's level and text: OK, 'running' unless a module says otherwise."""
        return DiagnosticStatus.OK, 'running'

    # -- common behaviour -------------------------------------------------------------------

    def warn(self, kind: str, message: str) -> None:
        """Log a warning, at most once per WARN_EVERY s for each kind.

        A stream of bad goals at 100 Hz must not flood the log, but a different problem is still
        reported at once.
        """
        now = time.monotonic()
        if now - self._last_warning.get(kind, -math.inf) >= WARN_EVERY:
            self._last_warning[kind] = now
            self.get_logger().warning(message)

    def _on_led(self, msg: Bool) -> None:
        if msg.data != self.led_on:
            self.get_logger().info(f"LED {'on' if msg.data else 'off'}")
        self.led_on = msg.data

    def _publish_button_change(self, parameters: list[Parameter]) -> None:
        if any(p.name == 'button_pressed' for p in parameters):
            self.switch_publisher.publish(Bool(data=self.get_parameter('button_pressed').value))

    def _warn_wrong_led_types(self) -> None:
        # A publisher of another type never reaches our Bool subscription; say so once per type.
        for info in self.get_publishers_info_by_topic(self.topic('led')):
            if info.topic_type != 'std_msgs/msg/Bool' and info.topic_type not in self._wrong_led_types:
                self._wrong_led_types.add(info.topic_type)
                self.get_logger().warning(
                    f"{self.topic('led')} is published as {info.topic_type} by "
                    f"{info.node_namespace.rstrip('/')}/{info.node_name}: the LED expects "
                    'std_msgs/msg/Bool and ignores it')

    def _publish_status(self) -> None:
        stamp = self.get_clock().now().to_msg()
        level, message = self.status_level()
        values = {
            'led': 'on' if self.led_on else 'off',
            'button': 'pressed' if self.get_parameter('button_pressed').value else 'released',
            'temperature': f'{self.temperature():.1f}',
            'uptime': f'{time.monotonic() - self.started:.0f}',
            'firmware': FIRMWARE_VERSION,
            **self.status_values(),
        }
        self.status_publisher.publish(DiagnosticStatus(
            level=level, name=self.topic('').rstrip('/'), message=message, hardware_id=self.serial,
            values=[KeyValue(key=k, value=v) for k, v in values.items()]))
        temperature = Temperature(temperature=self.temperature(), variance=0.25)
        temperature.header.stamp = stamp
        temperature.header.frame_id = f'{self.namespace_name}_base_link'
        self.temperature_publisher.publish(temperature)
        self.switch_publisher.publish(Bool(data=self.get_parameter('button_pressed').value))
        self._warn_wrong_led_types()


def run_module(make_node: Any, default_namespace: str, args: list[str] | None = None) -> None:
    """main() of a module executable: read the namespace, build the node, serve its page, spin.

    Spins until Ctrl-C; after the page's Restart Services or Reboot Device, starts again (restart.py).
    """
    OliveModule.handover = take_handover()
    built: list[OliveModule] = []

    def build() -> Node:
        node = make_node(read_namespace(default_namespace, sys.argv if args is None else args))
        built.append(node)
        try:
            node.start_page()
        except BaseException:
            # A bad address parameter ends the process with code 2; the node's 100 Hz threads must
            # not still be publishing while rclpy shuts down (a segfault at exit, seen once).
            node.destroy_node()
            raise
        return node

    spin_node(build, args, events=True)
    if built and built[0].restart_delay is not None:
        start_again(built[0].handover_state(), built[0].restart_delay)

