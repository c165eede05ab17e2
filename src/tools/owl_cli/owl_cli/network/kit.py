"""`owl network --kit`: each Olive module found, its ROS 2 distribution, one message each way.

A module is found by its node's name (`olive_<type>_<namespace>_dcm_srv`, the firmware's naming).
Its distribution is read off its endpoints: Humble's carry no type hash, Iron's and newer ones do.
From the module: one message on its main topic (the IMU's `imu`, a servo's `joint`, the camera's
`image/compressed`). To the module: a servo gets a goal equal to the position it reported (so
nothing moves), the IMU and the camera an `led` message switching their LED on; either counts once
the module's reader has acknowledged it (reliable DDS delivery), which shows the way in works.
A servo's `setTorqueEnable` must answer within 2 s (section 4.4 moves nothing without it); its
torque is then put back as it was: switched off again unless the answer says it was already on.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass
from typing import Any

from olive_kit.description import topic as module_topic

NODE_PATTERN = re.compile(r'olive_(imu|servo|camera)_([A-Za-z0-9_]+?)_dcm_srv')
MAIN_TOPICS = {'imu': ('imu', 'sensor_msgs/msg/Imu'), 'servo': ('joint', 'sensor_msgs/msg/JointState'),
               'camera': ('image/compressed', 'sensor_msgs/msg/CompressedImage')}
HUMBLE = 'ROS 2 Humble'
NEWER = 'ROS 2 Iron or newer'
ACK_TIMEOUT = 5.0  # seconds for the acknowledgements (Fast DDS asks for them every 3 s)
TORQUE_TIMEOUT = 2.0  # seconds for a servo's setTorqueEnable (and setTorqueDisable) to answer


@dataclass
class ModuleReport:
    """What `owl network --kit` learned of one Olive module; received and sent stay None when nothing went."""

    node: str
    module_type: str
    namespace: str
    distribution: str           # HUMBLE, NEWER, or 'unknown' (no endpoint seen)
    received: str | None = None  # what came from the module
    sent: str | None = None      # what the module acknowledged
    torque: str | None = None    # a servo: how its setTorqueEnable call went
    torque_ok: bool = False      # a servo: setTorqueEnable answered and the torque put back as it was

    def topic(self, name: str) -> str:
        """The absolute name of the module's topic name (olive_kit.description.topic)."""
        return module_topic(self.module_type, self.namespace, name)


def parse_module(node: str) -> tuple[str, str] | None:
    """(module type, namespace) of an Olive module's node name, or None for another node."""
    match = NODE_PATTERN.fullmatch(node.rsplit('/', 1)[-1])
    return (match.group(1), match.group(2)) if match else None


def distribution(type_hash_versions: list[int]) -> str:
    """Humble's endpoints have no type hash (version 0); from Iron on they carry RIHS01."""
    if not type_hash_versions:
        return 'unknown'
    return NEWER if any(version > 0 for version in type_hash_versions) else HUMBLE


def node_distribution(node: Any, name: str, namespace: str) -> str:
    """The ROS 2 distribution of another node, from the type hashes of its publishers.

    node is the rclpy Node that asks; 'unknown' for a node that has left meanwhile.
    """
    from rclpy.node import NodeNameNonExistentError

    try:
        topics = node.get_publisher_names_and_types_by_node(name, namespace)
    except NodeNameNonExistentError:
        return 'unknown'
    return distribution([info.topic_type_hash.version for topic, _ in topics
                         for info in node.get_publishers_info_by_topic(topic)
                         if info.node_name == name and info.node_namespace == namespace])


def torque_was_on(message: str) -> bool:
    """Whether a servo's answer to setTorqueEnable says its torque was on already.

    The simulated servo and the twins answer 'torque already enabled'; a real module's wording is not
    known, and an answer without 'already' counts as "was off", so the check switches it off again.
    """
    return 'already' in message.lower()


def torque_outcome(enabled: tuple[bool, str, float] | None, disabled: tuple[bool, str] | None,
                   timeout: float = TORQUE_TIMEOUT) -> tuple[bool, str]:
    """(ok, text) of a servo's torque check from its answers.

    enabled is setTorqueEnable's (success, message, seconds it took) or None (no answer); disabled is
    setTorqueDisable's (success, message), None when it was not called or did not answer.
    """
    if enabled is None:
        return False, (f'setTorqueEnable was not answered within {timeout:.0f} s (call it again: a Humble '
                       "module gives a new client's answer up after 0.1 s under load)")
    success, message, seconds = enabled
    text = f"setTorqueEnable answered in {seconds * 1000:.0f} ms ('{message}')"
    if not success:
        return False, f'{text} but failed'
    if torque_was_on(message):
        return True, f'{text}, torque left on'
    if disabled is None:
        return False, f'{text}, and setTorqueDisable did not answer within {timeout:.0f} s: its torque is ON'
    if not disabled[0]:
        return False, f"{text}, and setTorqueDisable failed ('{disabled[1]}'): its torque is ON"
    return True, f'{text}, torque switched off again'


def kit_verdicts(reports: list[ModuleReport]) -> list[tuple[bool, str]]:
    """(ok, text) per module, then a problem line when no module was found."""
    if not reports:
        return [(False, 'no Olive module node found, so nothing to check end to end; fix the problems '
                        'above first (network open, modules answering, the same ROS domain)')]
    verdicts = []
    for report in reports:
        where = f'{report.module_type} {report.namespace} (/{report.node}, {report.distribution})'
        missing = [way for way, done in (('nothing came from it', report.received),
                                         ('nothing sent to it was acknowledged', report.sent)) if not done]
        torque = ''
        if report.module_type == 'servo':
            if not report.torque_ok:
                missing.append(report.torque or torque_outcome(None, None)[1])
            torque = f'; {report.torque}'
        if missing:
            verdicts.append((False, f"{where}: {' and '.join(missing)}; fix: check the module's page "
                                    '(Log Monitor) and that no firewall blocks UDP 7400-7700'))
        else:
            verdicts.append((True, f'{where}: {report.received} from it, {report.sent} to it{torque}'))
    return verdicts


def not_yet_seen(expected: dict[str, str], seen: dict[str, str]) -> list[str]:
    """The expected nodes (name: distribution, as an earlier look found them) not seen as well yet.

    A node's name can come before its endpoints (a Humble module's name comes through the discovery
    bridge, its endpoints from DDS itself), and a node whose endpoints are not known yet has no
    known distribution.
    """
    return [name for name, distribution in expected.items()
            if name not in seen or (distribution != 'unknown' and seen[name] == 'unknown')]


def check_kit(domain_id: int, seconds: float, expected: dict[str, str]) -> list[ModuleReport]:
    """Find the Olive modules in the domain and exchange one message each way with all of them at once.

    Discovery takes seconds s, and up to ACK_TIMEOUT more while one of the expected nodes (name:
    distribution, as `owl network` found them a moment ago) is not seen as well yet; seconds also
    bounds the waits for the modules' messages and for their readers.
    """
    import rclpy
    from rclpy.context import Context
    from rclpy.duration import Duration
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node
    from rclpy.qos import qos_profile_sensor_data
    from sensor_msgs.msg import CompressedImage, Imu, JointState
    from std_msgs.msg import Bool, Float32

    types: dict[str, Any] = {'sensor_msgs/msg/Imu': Imu, 'sensor_msgs/msg/JointState': JointState,
                             'sensor_msgs/msg/CompressedImage': CompressedImage}
    context = Context()
    rclpy.init(context=context, domain_id=domain_id)
    try:
        node = Node('owl_network_kit_check', context=context)
        executor = SingleThreadedExecutor(context=context)
        executor.add_node(node)

        def spin_until(condition: Any, deadline: float) -> None:
            while not condition() and time.monotonic() < deadline:
                executor.spin_once(timeout_sec=0.05)

        def seen() -> dict[str, str]:
            return {name: node_distribution(node, name, namespace)
                    for name, namespace in node.get_node_names_and_namespaces() if name in expected}

        started = time.monotonic()
        spin_until(lambda: time.monotonic() >= started + seconds and not not_yet_seen(expected, seen()),
                   started + seconds + ACK_TIMEOUT)
        reports = sorted((ModuleReport(name, *parsed, node_distribution(node, name, namespace))
                          for name, namespace in node.get_node_names_and_namespaces()
                          if (parsed := parse_module(name)) is not None), key=lambda r: r.node)
        # From each module: one message on its main topic.
        received: dict[str, list[Any]] = {report.node: [] for report in reports}
        for report in reports:
            topic, type_name = MAIN_TOPICS[report.module_type]
            node.create_subscription(types[type_name], report.topic(topic), received[report.node].append,
                                     qos_profile_sensor_data)
        spin_until(lambda: all(received.values()), time.monotonic() + seconds)
        # To each module: one message, acknowledged by its reader. Fast DDS asks for
        # acknowledgements every 3 s (its heartbeat), so all are sent first and then waited for.
        sent: list[tuple[ModuleReport, Any, Any, str]] = []
        for report in reports:
            messages = received[report.node]
            topic, type_name = MAIN_TOPICS[report.module_type]
            if messages:
                report.received = f'one {type_name.rsplit("/", 1)[-1]} on {report.topic(topic)}'
            message: Any
            if report.module_type != 'servo':
                message, topic, what = Bool(data=True), report.topic('led'), 'one Bool (LED on)'
            elif messages and messages[-1].position:
                position = float(messages[-1].position[0])
                message, topic = Float32(data=position), report.topic('goal/position')
                what = f'one goal of {position:+.3f} rad (its position)'
            else:
                continue
            publisher = node.create_publisher(type(message), topic, 10)
            sent.append((report, publisher, message, f'{what} on {topic}'))
        spin_until(lambda: all(entry[1].get_subscription_count() for entry in sent),
                   time.monotonic() + seconds)
        # Two rounds: a reader only acknowledges once it knows our writer, but a volatile reader that
        # learns of us after a message was written acknowledges that message without taking it. After
        # the first acknowledgement it knows us, so the second message is taken when acknowledged.
        for _ in range(2):
            for entry in sent:
                if entry[1].get_subscription_count():
                    entry[1].publish(entry[2])
            deadline = time.monotonic() + ACK_TIMEOUT
            sent = [entry for entry in sent if entry[1].get_subscription_count()
                    and entry[1].wait_for_all_acked(Duration(seconds=max(0.0, deadline - time.monotonic())))]
        for report, _, _, what in sent:
            report.sent = what
        check_torque(node, [report for report in reports if report.module_type == 'servo'], seconds,
                     spin_until)
        node.destroy_node()
        return reports
    finally:
        rclpy.try_shutdown(context=context)


def check_torque(node: Any, servos: list[ModuleReport], seconds: float, spin_until: Any) -> None:
    """Call each servo's setTorqueEnable (all at once), then setTorqueDisable where the torque was off.

    Waits up to seconds for the services, TORQUE_TIMEOUT for each round of answers; fills the reports.
    """
    from std_srvs.srv import Trigger

    clients = {report.node: (node.create_client(Trigger, report.topic('setTorqueEnable')),
                             node.create_client(Trigger, report.topic('setTorqueDisable')))
               for report in servos}
    spin_until(lambda: all(enable.service_is_ready() and disable.service_is_ready()
                           for enable, disable in clients.values()), time.monotonic() + seconds)
    answered_at: dict[str, float] = {}
    calls: dict[str, tuple[float, Any]] = {}
    for report in servos:
        enable = clients[report.node][0]
        if enable.service_is_ready():
            future = enable.call_async(Trigger.Request())
            future.add_done_callback(
                lambda _, name=report.node: answered_at.setdefault(name, time.monotonic()))
            calls[report.node] = (time.monotonic(), future)
    spin_until(lambda: all(future.done() for _, future in calls.values()), time.monotonic() + TORQUE_TIMEOUT)
    enabled: dict[str, tuple[bool, str, float]] = {}
    restores: dict[str, Any] = {}
    for name, (started, future) in calls.items():
        if not future.done() or future.result() is None:
            continue
        response = future.result()
        took = answered_at.get(name, time.monotonic()) - started
        enabled[name] = (response.success, response.message, took)
        if response.success and not torque_was_on(response.message):
            restores[name] = clients[name][1].call_async(Trigger.Request())
    spin_until(lambda: all(future.done() for future in restores.values()), time.monotonic() + TORQUE_TIMEOUT)
    for report in servos:
        restore = restores.get(report.node)
        disabled = None
        if restore is not None and restore.done() and restore.result() is not None:
            disabled = (restore.result().success, restore.result().message)
        report.torque_ok, report.torque = torque_outcome(enabled.get(report.node), disabled)
    for enable, disable in clients.values():
        node.destroy_client(enable)
        node.destroy_client(disable)
