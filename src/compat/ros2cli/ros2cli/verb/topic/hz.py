"""`ros2 topic hz <topic>`: average publishing rate, min/max/std dev of the intervals."""

import argparse
import math
import sys
from collections import deque
from typing import Any

from owl_common.graph import expand_topic_name

from ros2cli.api.topic import _topic_argument, positive_int, receive_profile, wait_for_topic_type
from ros2cli.node.direct import DirectNode, add_direct_node_arguments
from ros2cli.verb import VerbExtension


class RateStatistics:
    """Arrival times in, rate statistics out, over the last `window` intervals (no ROS needed)."""

    def __init__(self, window: int) -> None:
        self.intervals: deque[float] = deque(maxlen=window)
        self.last_arrival: float | None = None
        self.last_report: float | None = None

    def add(self, arrival: float) -> bool:
        """Record one arrival (seconds); False when the clock went backwards (counters reset)."""
        if self.last_arrival is not None and arrival < self.last_arrival:
            self.intervals.clear()
            self.last_arrival = arrival
            self.last_report = arrival
            return False
        if self.last_arrival is not None:
            self.intervals.append(arrival - self.last_arrival)
        else:
            self.last_report = arrival
        self.last_arrival = arrival
        return True

    def due(self, now: float, period: float = 1.0) -> bool:
        """True at most once per period of arrival time, once there is an interval."""
        if not self.intervals or self.last_report is None or now - self.last_report < period:
            return False
        self.last_report = now
        return True

    def report(self) -> str:
        """The report upstream prints: average rate (Hz), then min, max and std dev of the intervals (s).

        Only for when there is an interval (due() says so): without one it divides by zero.
        """
        count = len(self.intervals)
        mean = sum(self.intervals) / count
        std_dev = math.sqrt(sum((i - mean) ** 2 for i in self.intervals) / count)
        rate = 1.0 / mean if mean > 0 else 0.0
        return (f'average rate: {rate:.3f}\n\tmin: {min(self.intervals):.3f}s '
                f'max: {max(self.intervals):.3f}s std dev: {std_dev:.5f}s window: {count}')


class HzVerb(VerbExtension):
    """Print the average publishing rate to screen."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, -w/--window, --filter, --wall-time and the DirectNode options."""
        _topic_argument(parser, "Name of the ROS topic to listen to (e.g. '/chatter')")
        parser.add_argument('--window', '-w', type=positive_int, default=10000,
                            help='window size, in # of messages, for calculating rate (default: 10000)')
        parser.add_argument('--filter', dest='filter_expr',
                            help='only measure messages matching the specified Python expression')
        parser.add_argument('--wall-time', action='store_true',
                            help='calculates rate using wall time which can be helpful when clock is not '
                                 'published during simulation')
        add_direct_node_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the topic's average rate about once a second until Ctrl-C, once the topic is in the graph.

        Times are the node's clock (sim time with -s) unless --wall-time; with --filter only the messages
        it accepts count (a malformed expression gives the error message).
        """
        # Lazy: rclpy and rosidl_runtime_py (yaml) import slowly; `ros2 topic -h` imports this module.
        from rclpy.clock import Clock, ClockType
        from rclpy.executors import SingleThreadedExecutor
        from rosidl_runtime_py.utilities import InvalidType, import_type

        topic = expand_topic_name(args.topic_name)
        predicate = None
        if args.filter_expr:
            try:
                predicate = eval(f'lambda m: {args.filter_expr}')  # the user's own expression
            except SyntaxError as error:
                return f"Invalid filter expression '{args.filter_expr}': {error.msg}"
        with DirectNode(args) as direct:
            types = wait_for_topic_type(direct, topic)
            try:
                message_class = import_type(types[0], 'msg')
            except InvalidType as error:
                return f"The message type '{types[0]}' is invalid: {error}"
            clock = Clock(clock_type=ClockType.STEADY_TIME) if args.wall_time else direct.node.get_clock()
            statistics = RateStatistics(args.window)
            raw = predicate is None  # nothing to look into: skip deserialising

            def on_message(message: Any) -> None:
                now = clock.now().nanoseconds / 1e9
                if predicate is not None and not predicate(message):
                    return
                if not statistics.add(now):
                    print('time has reset, resetting counters')
                elif statistics.due(now):
                    print(statistics.report())

            direct.node.create_subscription(message_class, topic, on_message, receive_profile(), raw=raw)
            executor = SingleThreadedExecutor(context=direct.node.context)
            executor.add_node(direct.node)
            while True:
                executor.spin_once(timeout_sec=0.5)
                sys.stdout.flush()
