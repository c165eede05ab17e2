"""humble_twin: one Olive module as a ROS 2 Humble module is on the wire, for tests and demos.

A real module runs ROS 2 Humble (Fast DDS). What makes it Humble on the wire, and what the twin
sends too: its graph message (ros_discovery_info) has 24-byte gids, and its endpoints carry no
type hash. The twin publishes an IMU's `Imu` (a fixed tilt, so `imu_turtle` drives the turtle) or
a servo's `JointState` following the goals it takes on `goal/position` (either takes `led`, as the
simulated modules do, and says when the LED changes), and it checks every graph
message it receives: one that does not parse in Humble's layout is printed and counted (a Humble
module would misread it).

Services are left out: Fast DDS pairs a reply with its request through an inline QoS field of the
DDS sample (related sample identity), which the Cyclone DDS Python API can neither read nor
write, so the twin's servo has no setTorqueEnable/Disable: owl_humble_fastdds's
humble_fastdds_twin, on Fast DDS itself, has them.
"""

from __future__ import annotations

import argparse
import math
import re
import signal
import sys
import time
from types import FrameType

from rclpy.serialization import deserialize_message, serialize_message
from sensor_msgs.msg import Imu, JointState
from std_msgs.msg import Bool, Float32

from owl_humble import discovery_info as info
from owl_humble import wire
from owl_humble.graph_partition import DISCOVERY_TOPIC, JAZZY_GRAPH_PARTITION
from owl_humble.launcher import ensure_discovery_bridge

PREFIX = 'humble_twin'
MODULE_TYPES = ('imu', 'servo')
NAMESPACE_PATTERN = re.compile(r'[A-Za-z][A-Za-z0-9_]*')
SERVO_SPEED = 3.0  # rad/s towards the goal, about the simulated servo's no-load speed
BRIDGED_WITHIN = 20.0  # s for the local bridge to forward the twin's graph message before it says ready


def ros_type(name: str) -> str:
    """The DDS type name of a ROS type: 'std_msgs/msg/Bool' -> 'std_msgs::msg::dds_::Bool_'."""
    package, kind, message = name.split('/')
    return f'{package}::{kind}::dds_::{message}_'


def node_name(module_type: str, namespace: str) -> str:
    """The node name of the module of this type and namespace, as on the real kit."""
    # The Olive firmware's naming (specs: /olive_servo_pan_dcm_srv), as olive_sim names its nodes.
    return f'olive_{module_type}_{namespace}_dcm_srv'


def say(text: str) -> None:
    """Print a line with the program's name, flushed at once: tests and demos read it as it comes."""
    print(f'{PREFIX}: {text}', flush=True)


class DiscoveryCheck:
    """Counts the graph messages the twin receives and those a Humble module would misread."""

    def __init__(self) -> None:
        self.received = 0
        self.malformed = 0

    def check(self, data: bytes, own_gid: bytes) -> None:
        """Count a received graph message (not the twin's own) and report one Humble would misread."""
        try:
            sample = info.decode(data, info.Layout.HUMBLE)
        except info.MalformedSample as error:
            self.received += 1
            self.malformed += 1
            layout = info.layout_of(data)
            sender = data[4:20].hex()
            say(f'malformed discovery sample #{self.malformed} (from participant {sender}, '
                f'{layout.name.title() if layout else "unknown"} layout): {error}; Humble would reserve '
                f'{info.humble_largest_allocation(data)} bytes reading it')
            return
        if sample.gid != own_gid:
            self.received += 1

    def summary(self) -> str:
        """The closing line: how many graph messages came and how many Humble would misread."""
        return f'discovery samples received: {self.received}, malformed in Humble\'s layout: {self.malformed}'


class Twin:
    """One module as a Humble module is on the wire: its participant, topics and graph message."""

    def __init__(self, module_type: str, namespace: str, rate: float, pitch: float) -> None:
        self.module_type = module_type
        self.prefix = f'/olive/{module_type}/{namespace}/'
        self.participant = wire.Participant()
        self.gid = self.participant.gid.ljust(24, b'\x00')
        self.period = 1.0 / rate
        self.pitch = pitch
        self.frame = f'{namespace}_base_link'
        self.position = 0.0
        self.goal: float | None = None
        self.check = DiscoveryCheck()
        self.discovery_reader = self.participant.reader(
            DISCOVERY_TOPIC, wire.DISCOVERY_TYPE, wire.discovery_reader_qos())
        self.discovery_writer = self.participant.writer(
            DISCOVERY_TOPIC, wire.DISCOVERY_TYPE, wire.discovery_writer_qos())
        self.led_on = False
        self.led_reader = self.participant.reader(
            'rt' + self.prefix + 'led', ros_type('std_msgs/msg/Bool'), wire.topic_qos())
        readers, writers = [self.led_reader], []
        if module_type == 'imu':
            self.imu_writer = self.participant.writer(
                'rt' + self.prefix + 'imu', ros_type('sensor_msgs/msg/Imu'), wire.topic_qos())
            writers.append(self.imu_writer)
        else:
            self.goal_reader = self.participant.reader(
                'rt' + self.prefix + 'goal/position', ros_type('std_msgs/msg/Float32'), wire.topic_qos())
            self.joint_writer = self.participant.writer(
                'rt' + self.prefix + 'joint', ros_type('sensor_msgs/msg/JointState'), wire.topic_qos())
            readers.append(self.goal_reader)
            writers.append(self.joint_writer)
        self.node = info.NodeEntities('/', node_name(module_type, namespace),
                                      [wire.entity_gid(r) for r in readers],
                                      [wire.entity_gid(w) for w in writers])
        wire.write(self.discovery_writer, info.encode(
            info.ParticipantEntities(self.participant.gid, [self.node]).in_layout(info.Layout.HUMBLE),
            info.Layout.HUMBLE))

    def step(self) -> None:
        """One tick: check the graph messages, follow the LED, publish the IMU reading or the joint state."""
        for sample in wire.take(self.discovery_reader):
            if sample.alive:
                self.check.check(sample.data, self.gid)
        for sample in wire.take(self.led_reader):
            led_on = sample.alive and deserialize_message(sample.data, Bool).data
            if sample.alive and led_on != self.led_on:
                say(f"LED {'on' if led_on else 'off'}")
                self.led_on = led_on
        if self.module_type == 'imu':
            self._publish_imu()
        else:
            self._follow_goals()

    def _stamp(self, header: object) -> None:
        now = time.time()
        header.stamp.sec, header.stamp.nanosec = int(now), int(now % 1 * 1e9)  # type: ignore[attr-defined]
        header.frame_id = self.frame  # type: ignore[attr-defined]

    def _publish_imu(self) -> None:
        message = Imu()
        self._stamp(message.header)
        message.orientation.y = math.sin(self.pitch / 2)
        message.orientation.w = math.cos(self.pitch / 2)
        message.linear_acceleration.x = -9.81 * math.sin(self.pitch)
        message.linear_acceleration.z = 9.81 * math.cos(self.pitch)
        wire.write(self.imu_writer, serialize_message(message))

    def _follow_goals(self) -> None:
        for sample in wire.take(self.goal_reader):
            if not sample.alive:
                continue
            goal = deserialize_message(sample.data, Float32).data
            say(f'goal {goal:+.3f} rad on {self.prefix}goal/position')
            if math.isfinite(goal):
                self.goal = goal
        if self.goal is not None:
            step = SERVO_SPEED * self.period
            self.position += max(-step, min(step, self.goal - self.position))
        joint = JointState()
        self._stamp(joint.header)
        joint.name = [self.node.name]
        joint.position = [self.position]
        wire.write(self.joint_writer, serialize_message(joint))


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    """The checked command line; a bad value exits with code 2 and one error line, as argparse does."""
    parser = argparse.ArgumentParser(
        prog=PREFIX, description='One Olive module as a ROS 2 Humble module is on the wire.')
    parser.add_argument('--module', choices=MODULE_TYPES, default='imu', help='the module type (default imu)')
    parser.add_argument('--namespace', default='humble', help="the module's namespace (default humble)")
    parser.add_argument('--rate', type=float, default=50.0, help='messages per second (default 50)')
    parser.add_argument('--pitch', type=float, default=0.3, help="the IMU's fixed pitch in rad (default 0.3)")
    args = parser.parse_args(argv)
    if not NAMESPACE_PATTERN.fullmatch(args.namespace):
        parser.error(f"--namespace '{args.namespace}' is not a ROS name (letters, digits, _; a letter first)")
    if not (math.isfinite(args.rate) and 0 < args.rate <= 1000):
        parser.error(f'--rate {args.rate} is not between 0 and 1000 messages per second')
    if not (math.isfinite(args.pitch) and abs(args.pitch) <= math.pi / 2):
        parser.error(f'--pitch {args.pitch} is not an angle between -pi/2 and pi/2')
    return args


def wait_until_bridged(twin: Twin, timeout: float) -> bool:
    """Wait until the bridge forwards the twin's graph message into our partition; False after timeout s.

    The bridge may have been started a moment ago: "ready" means our tools can list the node.
    """
    forwarded = twin.participant.reader(DISCOVERY_TOPIC, wire.DISCOVERY_TYPE, wire.discovery_reader_qos(),
                                        JAZZY_GRAPH_PARTITION)
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            for sample in wire.take(forwarded):
                layout = info.layout_of(sample.data) if sample.alive else None
                if layout is not None and info.decode(sample.data, layout).gid == twin.participant.gid:
                    return True
            time.sleep(0.02)
        return False
    finally:
        forwarded.__del__()


def main(argv: list[str] | None = None) -> None:
    """The humble_twin command: be the module until SIGINT or SIGTERM, then print the check's summary."""
    args = parse_args(sys.argv[1:] if argv is None else argv)
    stopping: list[int] = []

    def stop(signum: int, _frame: FrameType | None) -> None:
        stopping.append(signum)

    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGTERM, stop)
    twin = Twin(args.module, args.namespace, args.rate, args.pitch)
    if wire.ros_discovery_settings()[1] == 'LOCALHOST':
        # In open mode our tools start the bridge, as they do for a real module; in private mode
        # they do not (no real module can be there), so this stand-in starts it for its own demo.
        ensure_discovery_bridge(local_twin=True)
        if not wait_until_bridged(twin, BRIDGED_WITHIN):
            say(f'warning: the discovery bridge did not forward this node within {BRIDGED_WITHIN:.0f} s; '
                'our tools may not list it')
    say(f'ready: node /{twin.node.name} ({args.module}, ROS 2 Humble on the wire), participant '
        f'{twin.participant.gid.hex()} in domain {twin.participant.domain_id}')
    next_tick = time.monotonic()
    while not stopping:
        twin.step()
        next_tick += twin.period
        time.sleep(max(0.0, next_tick - time.monotonic()))
    say(twin.check.summary())  # the participant says goodbye on DDS as the process ends
