"""`ros2 bag record`: subscribe to topics (and service events) and write what arrives to a bag."""

from __future__ import annotations

import argparse
import re
import sys
import time
from pathlib import Path
from typing import Any

from ros2cli.api.topic import positive_int
from ros2cli.verb import VerbExtension

EVENT_SUFFIX = '/_service_event'
RECEIVE_DEPTH = 1000  # a burst waits in the queue while the recorder writes, instead of being dropped
ALWAYS_LEFT_OUT = ('/parameter_events', '/rosout')  # as upstream's --all (unless asked by name)


def regex(text: str) -> re.Pattern[str]:
    """An argparse type: the text as a compiled regular expression."""
    try:
        return re.compile(text)
    except re.error as error:
        raise argparse.ArgumentTypeError(f"'{text}' is not a regular expression: {error}") from None


class Selection:
    """Which topics of the graph the command line asks for."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.names = set(args.topics) | {s.rstrip('/') + EVENT_SUFFIX for s in args.services}
        self.all_topics = args.all or args.all_topics
        self.all_services = args.all or args.all_services
        self.regex: re.Pattern[str] | None = args.regex
        self.exclude: re.Pattern[str] | None = args.exclude_regex
        self.hidden = args.include_hidden_topics

    def wanted(self, topic: str) -> bool:
        """Whether to record the topic."""
        if self.exclude is not None and self.exclude.search(topic):
            return False
        if topic in self.names:
            return True
        if topic.endswith(EVENT_SUFFIX):
            return self.all_services
        if topic in ALWAYS_LEFT_OUT:
            return False
        if not self.hidden and any(part.startswith('_') for part in topic.split('/')):
            return False
        return self.all_topics or (self.regex is not None and bool(self.regex.search(topic)))

    def complete(self, subscribed: set[str]) -> bool:
        """Whether nothing more can be asked for: only named topics, all subscribed."""
        return not (self.all_topics or self.all_services or self.regex) and self.names <= subscribed


class RecordVerb(VerbExtension):
    """Record ROS data to a bag."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Topics, -a/--all, --all-topics, --all-services, --services, -e, -x, -o, -s, -p and more."""
        parser.add_argument('topics', nargs='*', default=[], help='List of topics to record.')
        parser.add_argument('-a', '--all', action='store_true',
                            help='Record all topics and services (Exclude hidden topic).')
        parser.add_argument('--all-topics', action='store_true',
                            help='Record all topics (Exclude hidden topic).')
        parser.add_argument('--all-services', action='store_true',
                            help='Record all services via service event topics.')
        parser.add_argument('--services', nargs='+', default=[], metavar='ServiceName',
                            help='List of services to record (their introspection must be on).')
        parser.add_argument('-e', '--regex', type=regex,
                            help='Record only topics containing provided regular expression.')
        parser.add_argument('--exclude-regex', type=regex,
                            help='Exclude topics containing provided regular expression.')
        parser.add_argument('--include-hidden-topics', action='store_true',
                            help='Record also hidden topics (topics starting with an underscore).')
        parser.add_argument('-o', '--output', help='Destination of the bagfile to create, defaults to a '
                            'timestamped folder in the current directory.')
        parser.add_argument('-s', '--storage', default='mcap', help="Storage identifier to be used, defaults "
                            "to 'mcap' (the only one here).")
        parser.add_argument('-p', '--polling-interval', type=positive_int, default=100,
                            help='Time in ms to wait between querying available topics for recording.')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Record until Ctrl-C; the bag's folder must not exist yet."""
        from ros2bag.bag import BagError, BagWriter, default_bag_name

        if not (args.topics or args.services or args.all or args.all_topics or args.all_services
                or args.regex):
            return ('Invalid choice: Must specify topic(s), --services, --all, --all-topics, --all-services '
                    'or --regex')
        if args.storage != 'mcap':
            return f"Invalid storage '{args.storage}': only 'mcap' bags are written here"
        folder = Path(args.output or default_bag_name())
        try:
            writer = BagWriter(folder)
        except BagError as error:
            return str(error)
        try:
            Recorder(args, writer).run()
        finally:
            writer.close()
        return 0


class Recorder:
    """The recording node: finds the wanted topics as they appear, subscribes, writes what arrives."""

    def __init__(self, args: argparse.Namespace, writer: Any) -> None:
        self.args = args
        self.writer = writer
        self.selection = Selection(args)
        self.subscriptions: dict[str, Any] = {}
        self.refused: set[str] = set()

    def run(self) -> None:
        """Spin until Ctrl-C, looking at the graph every polling interval until all is subscribed."""
        import rclpy
        from owl_common.run import begin_cleanup, init_with_stop_request

        stop = init_with_stop_request([])
        node = rclpy.create_node('rosbag2_recorder')
        log = node.get_logger()
        stop.polling = True
        log.info('Listening for topics...')
        discovering = True
        next_look = 0.0
        try:
            while rclpy.ok() and not stop.requested:
                if discovering and time.monotonic() >= next_look:
                    self.subscribe_new(node)
                    next_look = time.monotonic() + self.args.polling_interval / 1000
                    if self.selection.complete(set(self.subscriptions)):
                        log.info('All requested topics are subscribed. Stopping discovery...')
                        discovering = False
                rclpy.spin_once(node, timeout_sec=0.05)
        finally:
            begin_cleanup()
            count = self.writer.message_count
            plural = 's' if count != 1 else ''
            log.info(f"Recording stopped: {count} message{plural} in '{self.writer.folder}'")
            node.destroy_node()
            rclpy.try_shutdown()

    def subscribe_new(self, node: Any) -> None:
        """Subscribe to each wanted topic not subscribed yet whose type is known."""
        from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy

        from ros2bag.definitions import message_definition
        from ros2bag.interfaces import import_type, qos_yaml

        for topic, types in node.get_topic_names_and_types():
            if topic in self.subscriptions or topic in self.refused or not self.selection.wanted(topic):
                continue
            if len(types) != 1:
                node.get_logger().warning(f"Topic '{topic}' has several types ({', '.join(types)}): "
                                          'not recorded')
                self.refused.add(topic)
                continue
            try:
                message_class = import_type(types[0])
            except ValueError as error:
                node.get_logger().warning(f"Topic '{topic}' not recorded: {error}")
                self.refused.add(topic)
                continue
            publishers = node.get_publishers_info_by_topic(topic)
            if not publishers and topic not in self.selection.names:
                continue  # only subscribers so far: its publishers' QoS will decide ours
            # Without publishers yet (a topic asked for by name), the defaults: reliable, volatile.
            qos = QoSProfile(depth=RECEIVE_DEPTH)
            # Reliable and durable only when every publisher is, or some would not be heard.
            reliable = all(p.qos_profile.reliability == QoSReliabilityPolicy.RELIABLE for p in publishers)
            qos.reliability = QoSReliabilityPolicy.RELIABLE if reliable else QoSReliabilityPolicy.BEST_EFFORT
            durable = bool(publishers) and all(
                p.qos_profile.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL for p in publishers)
            qos.durability = QoSDurabilityPolicy.TRANSIENT_LOCAL if durable else QoSDurabilityPolicy.VOLATILE
            self.writer.add_topic(topic, types[0], message_definition(message_class),
                                  [qos_yaml(p.qos_profile) for p in publishers],
                                  str(publishers[0].topic_type_hash) if publishers else '')
            self.subscriptions[topic] = node.create_subscription(
                message_class, topic, lambda data, topic=topic: self.received(topic, data), qos, raw=True)
            node.get_logger().info(f"Subscribed to topic '{topic}'")
        sys.stdout.flush()

    def received(self, topic: str, data: bytes) -> None:
        """Write one message as it arrives."""
        self.writer.write(topic, data, time.time_ns())
