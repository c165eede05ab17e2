"""`ros2 topic bw <topic>`: bandwidth used by a topic (serialized message sizes per second)."""

import argparse
import time
from collections import deque
from typing import Any

from owl_common.graph import expand_topic_name

from ros2cli.api.topic import _topic_argument, positive_int, receive_profile, wait_for_topic_type
from ros2cli.node.direct import DirectNode, add_direct_node_arguments
from ros2cli.verb import VerbExtension


def size_text(size: float) -> str:
    """A byte count or rate as upstream shows it: '512 B', '2.00 KB', '3.50 MB' (units of 1000)."""
    for unit, scale in (('MB', 1e6), ('KB', 1e3)):
        if size >= scale:
            return f'{size / scale:.2f} {unit}'
    return f'{size:.0f} B'


class BandwidthStatistics:
    """(arrival time, size) samples in, a bandwidth report out, over the last `window` messages."""

    def __init__(self, window: int) -> None:
        self.samples: deque[tuple[float, int]] = deque(maxlen=window)

    def add(self, arrival: float, size: int) -> None:
        """Record one message: its arrival time (seconds) and its serialized size (bytes)."""
        self.samples.append((arrival, size))

    def report(self) -> str | None:
        """The bandwidth and message size report, or None while there are fewer than two messages."""
        if len(self.samples) < 2:
            return None
        sizes = [size for _, size in self.samples]
        # The bytes that arrived after the first sample, over the time they took.
        elapsed = self.samples[-1][0] - self.samples[0][0]
        rate = sum(sizes[1:]) / elapsed if elapsed > 0 else 0.0
        mean = size_text(sum(sizes) / len(sizes))
        return (f'{size_text(rate)}/s from {len(sizes)} messages\n\tMessage size mean: {mean} '
                f'min: {size_text(min(sizes))} max: {size_text(max(sizes))}')


class BwVerb(VerbExtension):
    """Display bandwidth used by topic."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, -w/--window and the DirectNode options."""
        _topic_argument(parser, "Name of the ROS topic to listen to (e.g. '/chatter')")
        parser.add_argument('--window', '-w', type=positive_int, default=100,
                            help='maximum window size, in # of messages, for calculating rate (default: 100)')
        add_direct_node_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the topic's bandwidth once a second until Ctrl-C, once the topic is in the graph.

        Messages are received serialized and never deserialized; a message type that cannot be imported
        gives the error message.
        """
        # Lazy: rclpy and rosidl_runtime_py (yaml) import slowly; `ros2 topic -h` imports this module.
        from rclpy.executors import SingleThreadedExecutor
        from rosidl_runtime_py.utilities import InvalidType, import_type

        topic = expand_topic_name(args.topic_name)
        with DirectNode(args) as direct:
            types = wait_for_topic_type(direct, topic)
            try:
                message_class = import_type(types[0], 'msg')
            except InvalidType as error:
                return f"The message type '{types[0]}' is invalid: {error}"
            statistics = BandwidthStatistics(args.window)

            def on_message(data: Any) -> None:
                statistics.add(time.monotonic(), len(data))

            direct.node.create_subscription(message_class, topic, on_message, receive_profile(), raw=True)
            print(f'Subscribed to [{topic}]')
            executor = SingleThreadedExecutor(context=direct.node.context)
            executor.add_node(direct.node)
            next_report = time.monotonic() + 1.0
            while True:
                executor.spin_once(timeout_sec=max(0.0, next_report - time.monotonic()))
                if time.monotonic() >= next_report:
                    next_report += 1.0
                    text = statistics.report()
                    if text:
                        print(text)
