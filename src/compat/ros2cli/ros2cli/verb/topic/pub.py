"""`ros2 topic pub <topic> <type> [values]`: publish a message given as YAML, once, N times or at a rate."""

import argparse
import time
from typing import Any

from owl_common.graph import expand_topic_name

from ros2cli.api.topic import (
    _topic_argument,
    _type_argument,
    add_values_arguments,
    positive_float,
    read_values,
)
from ros2cli.node.direct import DirectNode, add_direct_node_arguments
from ros2cli.qos import add_qos_arguments, profile_from_args
from ros2cli.verb import VerbExtension

# A subscriber that our writer has matched may not yet have matched our writer (each side learns of
# the other from its own discovery message) and drops what it receives until it has; a pause after
# the wait for subscriptions lets it catch up, so -1/--times reach `ros2 topic echo` on a busy machine.
MATCH_SETTLE = 0.3


def nonnegative_int(text: str) -> int:
    """An argparse type: the text as an int, ArgumentTypeError when it is below zero."""
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f'{text} is not a non-negative integer')
    return value


class PubVerb(VerbExtension):
    """Publish a message to a topic."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name and type, the values, and the rate, count, wait, QoS and DirectNode options."""
        _topic_argument(parser, "Name of the ROS topic to publish to (e.g. '/chatter')")
        _type_argument(parser, help_text="Type of the ROS message (e.g. 'std_msgs/String')")
        add_values_arguments(parser, 'message', 'data: Hello World')
        parser.add_argument('-r', '--rate', metavar='N', type=positive_float, default=1.0,
                            help='Publishing rate in Hz (default: 1)')
        parser.add_argument('-p', '--print', metavar='N', type=int, default=1,
                            help='Only print every N-th published message (default: 1)')
        group = parser.add_mutually_exclusive_group()
        group.add_argument('-1', '--once', action='store_true', help='Publish one message and exit')
        group.add_argument('-t', '--times', type=nonnegative_int, default=0,
                           help='Publish this number of times and then exit')
        parser.add_argument('-w', '--wait-matching-subscriptions', type=nonnegative_int, default=None,
                            help='Wait until finding the specified number of matching subscriptions. '
                                 'Defaults to 1 when using "-1"/"--once"/"--times", otherwise defaults to 0.')
        parser.add_argument('--max-wait-time-secs', type=positive_float, default=None,
                            help='Maximum time in seconds to wait for matching subscriptions (default: wait '
                                 'forever)')
        parser.add_argument('--keep-alive', metavar='N', type=positive_float, default=0.1,
                            help='Keep publishing node alive for N seconds after the last msg (default: 0.1)')
        parser.add_argument('-n', '--node-name', help='Name of the created publishing node')
        add_qos_arguments(parser, 'publish', 'default')
        add_direct_node_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Publish the message made of the YAML values at --rate Hz: once (-1), N times (-t) or until Ctrl-C.

        With -1 or -t it first waits for a matching subscription (see -w, and MATCH_SETTLE). An invalid
        type or field, or a wait that times out, gives the error message.
        """
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 topic -h` imports this module.
        from rosidl_runtime_py.set_message import FieldError, set_message_fields
        from rosidl_runtime_py.utilities import InvalidType, import_type

        times = 1 if args.once else args.times
        wait_count = args.wait_matching_subscriptions
        if wait_count is None:
            wait_count = 1 if times else 0
        if wait_count == 0 and args.max_wait_time_secs is not None:
            return ('--max-wait-time-secs option is only effective with --wait-matching-subscriptions, '
                    '--once or --times')
        try:
            message_class = import_type(args.message_type, 'msg')
        except InvalidType as error:
            return f'The passed message type is invalid: {error}'
        values = read_values(args, 'field')
        if not isinstance(values, dict) and values is not None:
            return 'The passed value needs to be a dictionary in YAML format'
        message = message_class()
        try:
            # `header: auto` and `stamp: now` are filled in before each publish.
            stamps = set_message_fields(message, values, expand_header_auto=True, expand_time_now=True)
        except FieldError as error:
            return f'Failed to populate field: {error}'

        with DirectNode(args, node_name=args.node_name) as direct:
            node = direct.node
            publisher = node.create_publisher(message_class, expand_topic_name(args.topic_name),
                                              profile_from_args(args))
            if wait_count and not self._wait_for_subscriptions(direct, publisher, wait_count,
                                                               args.max_wait_time_secs):
                return (f'Timed out waiting for subscribers: Expected {wait_count} subcribers but only got '
                        f'{publisher.get_subscription_count()} subscribers')
            if wait_count:
                direct.spin_for(MATCH_SETTLE)
            print('publisher: beginning loop')
            self._publish_loop(direct, publisher, message, stamps, times, args)
        return 0

    @staticmethod
    def _wait_for_subscriptions(direct: Any, publisher: Any, count: int, max_wait: float | None) -> bool:
        start = time.monotonic()
        next_notice = start
        while publisher.get_subscription_count() < count:
            now = time.monotonic()
            if now >= next_notice:
                print(f'Waiting for at least {count} matching subscription(s)...')
                next_notice += 1.0
            if max_wait is not None and now - start >= max_wait:
                return False
            direct.spin_for(0.1)
        return True

    @staticmethod
    def _publish_loop(direct: Any, publisher: Any, message: Any, stamps: list[Any], times: int,
                      args: argparse.Namespace) -> None:
        # Lazy: rclpy is slow to import, and `ros2 topic -h` imports this module.
        from rclpy.executors import SingleThreadedExecutor

        node = direct.node
        count = 0

        def publish() -> None:
            nonlocal count
            if stamps:
                now = node.get_clock().now().to_msg()
                for refresh in stamps:
                    refresh(now)
            publisher.publish(message)
            count += 1
            if args.print > 0 and count % args.print == 0:
                print(f'publishing #{count}: {message!r}\n')

        publish()
        if times != 1:
            timer = node.create_timer(1.0 / args.rate, publish)
            executor = SingleThreadedExecutor(context=node.context)
            executor.add_node(node)
            while times == 0 or count < times:
                executor.spin_once(timeout_sec=0.5)
            timer.cancel()
            executor.remove_node(node)
        time.sleep(args.keep_alive)
