"""`ros2 bag play <bag>`: publish a bag's messages again, with their recorded timing."""

from __future__ import annotations

import argparse
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from ros2cli.api.topic import positive_float
from ros2cli.verb import VerbExtension

MATCH_WAIT = 2.0  # s: the longest play waits for the graph's subscribers to match before it plays
# s without a change in a complete graph before play looks for its subscribers, and the longest it
# waits once the graph is complete: a participant's subscriptions are announced apart from its
# publications and can come later. In suite runs a held-up listener's /chatter subscription came
# after 0.3 s of quiet in 5 of 9 tries (it missed the first 1-4 messages); the `ros2` graph verbs
# wait 0.05 s and 1.2 s, for they lose nothing by answering early.
GRAPH_QUIET = 1.0
GRAPH_MOST = 2.0
# s: the longest play then waits for the readers of a participant it knows only the writers of.
# A participant announces its readers apart from its writers: a listener held up while play started
# on a loaded machine had all its readers (its /chatter subscription among them) come 0.4-0.65 s
# after its writers, after discovery had settled (4 of 30 tries; that listener used UDP only). Every
# ROS 2 participant has a reader (rmw's own, of ros_discovery_info), so only a late one is waited for.
READERS_WAIT = 1.0
# s: then how long it gives the subscribers to match the player in turn. DDS matches the two ends
# one at a time, and a volatile reader drops what arrives before its end has matched; a listener
# that was held up while play started lost the first message once, matched within 0.1 s of play.
READER_MATCH = 0.3
# s: at the end, the longest play waits for its subscribers to acknowledge what it sent: a
# publication is sent on a thread of rmw's own, and a player that exits at once lost its last message
ACK_WAIT = 1.0


def non_negative_float(text: str) -> float:
    """An argparse type: the text as a float, ArgumentTypeError when it is below zero."""
    value = float(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f'{text} is negative')
    return value


def remapping(text: str) -> tuple[str, str]:
    """An argparse type: 'old:=new' as (old, new)."""
    old, sep, new = text.partition(':=')
    if not sep or not old or not new:
        raise argparse.ArgumentTypeError(f"'{text}' is not a remapping like /old:=/new")
    return old, new


class PlayVerb(VerbExtension):
    """Play back ROS data from a bag."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """The bag; -r/--rate, -l/--loop, --topics, --remap, -d/--delay, --start-offset, -s/--storage."""
        parser.add_argument('bag_path', help='Bag to open')
        parser.add_argument('-s', '--storage', default='mcap',
                            help="Storage implementation of bag (only 'mcap').")
        parser.add_argument('-r', '--rate', type=positive_float, default=1.0,
                            help='rate at which to play back messages. Valid range > 0.0.')
        parser.add_argument('-l', '--loop', action='store_true',
                            help='enables loop playback when playing a bagfile: it starts back at the '
                                 'beginning on reaching the end and plays indefinitely.')
        parser.add_argument('--topics', nargs='+', default=None, help='topics to replay, separated by space. '
                            'If none specified, all topics will be replayed.')
        parser.add_argument('--remap', '-m', nargs='+', type=remapping, default=[],
                            help='list of topics to be remapped: in the form "old_topic1:=new_topic1 ..."')
        parser.add_argument('-d', '--delay', type=non_negative_float, default=0.0,
                            help='Sleep duration before play (each loop), in seconds. Negative durations '
                                 'invalid.')
        parser.add_argument('--start-offset', type=non_negative_float, default=0.0,
                            help='Start the playback player this many seconds into the bag file.')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Publish every message at its recorded moment (scaled by --rate) until the end or Ctrl-C."""
        from ros2bag.bag import BagError, read_metadata

        folder = Path(args.bag_path)
        try:
            info = read_metadata(folder)
        except BagError as error:
            return str(error)
        recorded = {t['topic_metadata']['name']: t['topic_metadata']['type']
                    for t in info.get('topics_with_message_count', [])}
        if args.topics is not None:
            unknown = [t for t in args.topics if t not in recorded]
            if unknown:
                held = ', '.join(sorted(recorded))
                return f"Topic(s) not in the bag: {', '.join(unknown)} (it holds {held})"
        try:
            return play(folder, args, recorded)
        except BagError as error:
            return str(error)


def play(folder: Path, args: argparse.Namespace, recorded: dict[str, str]) -> int | str:
    """Publish the bag's messages; 0 at the end, or at Ctrl-C."""
    import rclpy
    from owl_common.run import begin_cleanup, init_with_stop_request
    from rclpy.qos import QoSProfile

    from ros2bag.interfaces import import_type

    stop = init_with_stop_request([])
    node = rclpy.create_node('rosbag2_player')
    stop.polling = True
    remaps = dict(args.remap)
    publishers: dict[str, Any] = {}
    wanted = set(args.topics) if args.topics is not None else None
    try:
        for topic, type_name in recorded.items():
            if wanted is not None and topic not in wanted:
                continue
            try:
                publishers[topic] = node.create_publisher(import_type(type_name), remaps.get(topic, topic),
                                                          QoSProfile(depth=1000))
            except ValueError as error:
                node.get_logger().warning(f"Topic '{topic}' is not played: {error}")
        count = len(publishers)
        node.get_logger().info(f"Playing '{folder}' ({count} topic{'s' if count != 1 else ''})")
        wait_for_subscribers(node, publishers)
        while True:
            if not sleep_unless_stopped(args.delay, stop):
                break
            if not play_once(folder, args, publishers, stop):
                break
            if not args.loop:
                wait_for_acknowledgements(publishers)
                break
    finally:
        begin_cleanup()
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


def wait_for_subscribers(node: Any, publishers: dict[str, Any]) -> None:
    """Spin until discovery has settled and every subscription it shows on a played topic has matched.

    Messages published before a subscriber has matched are lost to it (the tutorial's turtle then
    drove a shorter curve). The graph must be complete first: on a busy machine a fixed 0.3 s once
    showed no subscriber yet, and the replayed curve came out 0.4 rad short; so must each
    participant's readers (READERS_WAIT). Matching then takes at most MATCH_WAIT, and a subscriber's
    own end READER_MATCH more.
    """
    import rclpy
    from ros2cli.node.direct import settle_discovery

    settle_discovery(node, quiet_complete=GRAPH_QUIET, most=GRAPH_MOST)
    if wait_for_readers(node):
        settle_discovery(node, quiet_complete=GRAPH_QUIET, most=GRAPH_MOST)  # the rest of those readers
    deadline = time.monotonic() + MATCH_WAIT
    while not all(publisher.get_subscription_count() >= node.count_subscribers(publisher.topic_name)
                  for publisher in publishers.values()):
        if time.monotonic() >= deadline:
            return
        rclpy.spin_once(node, timeout_sec=0.05)
    if any(publisher.get_subscription_count() for publisher in publishers.values()):
        time.sleep(READER_MATCH)  # DDS's own threads do the matching


def wait_for_readers(node: Any) -> bool:
    """Spin until each participant in the graph has a reader (READERS_WAIT s at most); True if it waited."""
    import rclpy

    deadline = time.monotonic() + READERS_WAIT
    waited = False
    while writers_without_readers(graph_endpoints(node)) and time.monotonic() < deadline:
        waited = True
        rclpy.spin_once(node, timeout_sec=0.05)
    return waited


def graph_endpoints(node: Any) -> list[tuple[bytes, bool]]:
    """(participant, is a reader) of every endpoint the graph shows, rmw's and services' included."""
    endpoints = []
    for name, _ in node.get_topic_names_and_types(no_demangle=True):
        endpoints += [(bytes(info.endpoint_gid[:12]), False)
                      for info in node.get_publishers_info_by_topic(name, no_mangle=True)]
        endpoints += [(bytes(info.endpoint_gid[:12]), True)
                      for info in node.get_subscriptions_info_by_topic(name, no_mangle=True)]
    return endpoints


def writers_without_readers(endpoints: Iterable[tuple[bytes, bool]]) -> set[bytes]:
    """The participants with a writer and no reader among endpoints, each (participant, is a reader)."""
    endpoints = list(endpoints)
    with_readers = {participant for participant, is_reader in endpoints if is_reader}
    return {participant for participant, is_reader in endpoints if participant not in with_readers}


def wait_for_acknowledgements(publishers: dict[str, Any]) -> None:
    """Give the subscribers up to ACK_WAIT s in all to acknowledge every message played."""
    from rclpy.duration import Duration

    deadline = time.monotonic() + ACK_WAIT
    for publisher in publishers.values():
        publisher.wait_for_all_acked(Duration(seconds=max(0.0, deadline - time.monotonic())))


def sleep_unless_stopped(seconds: float, stop: Any) -> bool:
    """Sleep; False when a stop was requested meanwhile."""
    deadline = time.monotonic() + seconds
    while not stop.requested and (left := deadline - time.monotonic()) > 0:
        time.sleep(min(left, 0.05))
    return not stop.requested


def play_once(folder: Path, args: argparse.Namespace, publishers: dict[str, Any], stop: Any) -> bool:
    """One pass through the bag; False when stopped."""
    from ros2bag.bag import messages

    start_bag: int | None = None
    start_wall = time.monotonic()
    offset = int(args.start_offset * 1e9)
    for message in messages(folder, set(publishers)):
        if start_bag is None:
            start_bag = message.log_time + offset
        if message.log_time < start_bag:
            continue
        due = start_wall + (message.log_time - start_bag) / 1e9 / args.rate
        if not sleep_unless_stopped(due - time.monotonic(), stop):
            return False
        publishers[message.topic].publish(message.data)
    return not stop.requested
