"""Topics and QoS: what the ROS graph shows, looked at once for every check and report of a run."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

from ros2doctor.api import DoctorCheck, DoctorReport, Report, Result
from ros2doctor.api.format import doctor_error, doctor_warn
from ros2doctor.api.network import domain_id_problem

# Every node has these; a publisher without subscribers there says nothing.
ALWAYS_THERE = ('/parameter_events', '/rosout')


@dataclass
class TopicEndpoints:
    """One topic of the graph with its publishers and subscriptions (rclpy's TopicEndpointInfo)."""

    name: str
    types: list[str]
    publishers: list[Any]
    subscriptions: list[Any]


@functools.cache
def graph_topics() -> list[TopicEndpoints]:
    """Every topic of the graph and its endpoints, once discovery has settled (asked once a run).

    None with a ROS_DOMAIN_ID no node can use (the network check says so): Fast DDS would end the
    process.
    """
    # Lazy: rclpy is slow to import, and `ros2 -h` imports the command module.
    from ros2cli.node.direct import DirectNode

    if domain_id_problem() is not None:
        return []

    with DirectNode() as direct:
        node = direct.node
        return [TopicEndpoints(name, list(types), node.get_publishers_info_by_topic(name),
                               node.get_subscriptions_info_by_topic(name))
                for name, types in node.get_topic_names_and_types()]


def compatibility(publisher_qos: Any, subscription_qos: Any) -> tuple[str, str]:
    """('OK' | 'WARNING' | 'ERROR', the reason rmw gives) for one publisher and one subscription."""
    from rclpy.qos import QoSCompatibility, qos_check_compatible

    verdict, reason = qos_check_compatible(publisher_qos, subscription_qos)
    return {QoSCompatibility.OK: 'OK', QoSCompatibility.WARNING: 'WARNING'}.get(verdict, 'ERROR'), reason


class TopicCheck(DoctorCheck):
    """Topics that are published with nobody listening, or listened to with nobody publishing."""

    def category(self) -> str:
        """'topic'."""
        return 'topic'

    def check(self) -> Result:
        """A warning per one-sided topic (/parameter_events and /rosout left out)."""
        result = Result()
        for topic in graph_topics():
            if topic.name in ALWAYS_THERE:
                continue
            if topic.publishers and not topic.subscriptions:
                doctor_warn(f'Publisher without subscriber detected on {topic.name}.')
                result.add_warning()
            elif topic.subscriptions and not topic.publishers:
                doctor_warn(f'Subscriber without publisher detected on {topic.name}.')
                result.add_warning()
        return result


class TopicReport(DoctorReport):
    """TOPIC LIST: each topic and how many publish and subscribe."""

    def category(self) -> str:
        """'topic'."""
        return 'topic'

    def report(self) -> Report:
        """topic, publisher count, subscriber count per topic (none: 'none', 0, 0)."""
        report = Report('TOPIC LIST')
        topics = [t for t in graph_topics() if t.name not in ALWAYS_THERE]
        for topic in topics:
            report.add_to_report('topic', topic.name)
            report.add_to_report('publisher count', len(topic.publishers))
            report.add_to_report('subscriber count', len(topic.subscriptions))
        if not topics:
            for key, value in (('topic', 'none'), ('publisher count', 0), ('subscriber count', 0)):
                report.add_to_report(key, value)
        return report


def _strip_level(reason: str) -> str:
    for prefix in ('WARNING: ', 'ERROR: '):
        if reason.upper().startswith(prefix):
            return reason[len(prefix):]
    return reason


class QoSCompatibilityCheck(DoctorCheck):
    """Publishers and subscriptions of a topic whose QoS keeps them from talking."""

    def category(self) -> str:
        """'middleware'."""
        return 'middleware'

    def check(self) -> Result:
        """An error per incompatible pair, a warning per pair that may not talk."""
        result = Result()
        for topic in graph_topics():
            for publisher in topic.publishers:
                for subscription in topic.subscriptions:
                    verdict, reason = compatibility(publisher.qos_profile, subscription.qos_profile)
                    if verdict == 'ERROR':
                        doctor_error(f"QoS compatibility error found on topic '{topic.name}': "
                                     f'{_strip_level(reason)}')
                        result.add_error()
                    elif verdict == 'WARNING':
                        doctor_warn(f"QoS compatibility warning found on topic '{topic.name}': "
                                    f'{_strip_level(reason)}')
                        result.add_warning()
        return result


class QoSCompatibilityReport(DoctorReport):
    """QOS COMPATIBILITY LIST: each publisher/subscription pair and whether their QoS fit."""

    def category(self) -> str:
        """'middleware'."""
        return 'middleware'

    def report(self) -> Report:
        """Topic [type], publisher node, subscriber node, compatibility status per pair."""
        report = Report('QOS COMPATIBILITY LIST')
        for topic in graph_topics():
            for publisher in topic.publishers:
                for subscription in topic.subscriptions:
                    verdict, reason = compatibility(publisher.qos_profile, subscription.qos_profile)
                    report.add_to_report('topic [type]', f'{topic.name} [{publisher.topic_type}]')
                    report.add_to_report('publisher node', publisher.node_name)
                    report.add_to_report('subscriber node', subscription.node_name)
                    report.add_to_report('compatibility status', 'OK' if verdict == 'OK' else reason)
        if not report.items:
            report.add_to_report('compatibility status', 'No publisher/subscriber pairs found')
        return report
