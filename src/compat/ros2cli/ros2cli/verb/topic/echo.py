"""`ros2 topic echo <topic> [type]`: print the messages of a topic as YAML (or CSV, raw bytes)."""

import argparse
import sys
import time
from typing import TYPE_CHECKING, Any

from owl_common.graph import expand_topic_name, matching_policies

from ros2cli.api.topic import (
    RECEIVE_DEPTH,
    _topic_argument,
    _type_argument,
    non_negative_int,
    positive_float,
    topic_types,
    unknown_topic,
)
from ros2cli.node.direct import NAMED_LOOKUP_GRACE, DirectNode
from ros2cli.node.strategy import add_strategy_arguments
from ros2cli.qos import add_qos_arguments, has_overrides, profile_from_args
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # rclpy is imported where it is used: `ros2 topic -h` imports this module
    from rclpy.qos import QoSProfile

# What upstream (Jazzy) shows of a message's receive information (printed with sorted keys).
MESSAGE_INFO_KEYS = ('publication_sequence_number', 'reception_sequence_number', 'received_timestamp',
                     'source_timestamp')

RELIABLE_FALLBACK = ('Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. Falling back '
                     'to QoSReliabilityPolicy.BEST_EFFORT as it will connect to all publishers')
DURABLE_FALLBACK = ('Some, but not all, publishers are offering QoSDurabilityPolicy.TRANSIENT_LOCAL. Falling '
                    'back to QoSDurabilityPolicy.VOLATILE as it will connect to all publishers')


def add_message_output_arguments(parser: argparse.ArgumentParser, with_field: bool = True) -> None:
    """The formatting options echo shares with other message printers (`ros2 service echo` has no --field)."""
    parser.add_argument('--csv', action='store_true', help='Output all recursive fields separated by commas '
                        '(e.g. for plotting)')
    if with_field:
        parser.add_argument('--field', type=str, default=None,
                            help="Echo a selected field of a message. Use '.' to select sub-fields. For "
                                 'example, to echo the position field of a nav_msgs/msg/Odometry message: '
                                 "'ros2 topic echo /odom --field pose.pose.position'")
    parser.add_argument('--full-length', '-f', action='store_true',
                        help='Output all elements for arrays, bytes, and string with a length > '
                             '\'--truncate-length\', by default they are truncated after '
                             '\'--truncate-length\' elements with \'...\'')
    parser.add_argument('--truncate-length', '-l', type=non_negative_int, default=128,
                        help='The length to truncate arrays, bytes, and string to (default: 128)')
    parser.add_argument('--no-arr', action='store_true', help="Don't print array fields of messages")
    parser.add_argument('--no-str', action='store_true', help="Don't print string fields of messages")
    parser.add_argument('--flow-style', action='store_true', help='Print collections in the block style '
                        '(not available with csv format)')


def choose_qos(args: argparse.Namespace, publishers: list[dict[str, Any]]) -> 'QoSProfile':
    """Explicit policies win; otherwise match the publishers (reliable/durable only if all are)."""
    # Lazy: rclpy is slow to import, and `ros2 topic -h` imports this module.
    from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

    profile = profile_from_args(args)
    if has_overrides(args):
        return profile
    # A deeper queue than the preset's 5: a burst that arrives while a message is being printed
    # waits instead of being dropped (the preset's purpose is its policies, not its depth).
    profile.depth = max(profile.depth, RECEIVE_DEPTH)
    if not publishers:
        return profile
    reliability, durability = matching_policies(publishers)
    if reliability == 'BEST_EFFORT' and any(p['reliability'] == 'RELIABLE' for p in publishers):
        print(RELIABLE_FALLBACK)
    if durability == 'VOLATILE' and any(p['durability'] == 'TRANSIENT_LOCAL' for p in publishers):
        print(DURABLE_FALLBACK)
    profile.reliability = ReliabilityPolicy[reliability]
    profile.durability = DurabilityPolicy[durability]
    return profile


class MessagePrinter:
    """Formats received messages as the options ask: matches() filters, format() gives the text to print."""

    def __init__(self, args: argparse.Namespace) -> None:
        self.args = args
        self.truncate = None if args.full_length else args.truncate_length
        self.field_path: list[str] | None = None
        if args.field is not None:
            self.field_path = [part for part in args.field.split('.') if part]
            if not self.field_path:
                raise RuntimeError(f"Invalid field value '{args.field}'")
        self.predicate = None
        if getattr(args, 'filter_expr', None):
            try:
                self.predicate = eval(f'lambda m: {args.filter_expr}')  # the user's own expression
            except SyntaxError as error:
                raise RuntimeError(f"Invalid filter expression '{args.filter_expr}': {error.msg}") from None

    def matches(self, message: Any) -> bool:
        """Whether the message passes --filter (always without one); RuntimeError if the expression fails."""
        if self.predicate is None:
            return True
        try:
            return bool(self.predicate(message))
        except Exception as error:
            raise RuntimeError(f"Filter expression '{self.args.filter_expr}' failed: "
                               f'{type(error).__name__}: {error}') from None

    def select(self, message: Any) -> Any:
        """The --field part of the message (all of it without --field); RuntimeError for a missing field."""
        value = message
        for part in self.field_path or []:
            try:
                value = getattr(value, part)
            except AttributeError:
                raise RuntimeError(f"Invalid field '{self.args.field}': '{type(value).__name__}' object has "
                                   f"no attribute '{part}'") from None
        return value

    def format(self, message: Any) -> str:
        """The text to print: YAML ending in '---', or a CSV line for --csv (str() of a non-message field)."""
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 topic -h` imports this module.
        from rosidl_runtime_py.convert import message_to_csv, message_to_yaml
        from rosidl_runtime_py.utilities import is_message

        value = self.select(message)
        args = self.args
        if not is_message(value):
            return f'{value}\n---' if not args.csv else str(value)
        if args.csv:
            return message_to_csv(value, truncate_length=self.truncate, no_arr=args.no_arr,
                                  no_str=args.no_str)
        return message_to_yaml(value, truncate_length=self.truncate, no_arr=args.no_arr, no_str=args.no_str,
                               flow_style=args.flow_style) + '---'


class EchoVerb(VerbExtension):
    """Output messages from a topic."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, the optional type, and the NodeStrategy, QoS and output options.

        Then echo's own: --no-lost-messages, --raw, --filter, --once, --timeout and -i. The QoS
        profile defaults to sensor_data, fitted to the publishers (see choose_qos).
        """
        add_strategy_arguments(parser)
        _topic_argument(parser, "Name of the ROS topic to listen to (e.g. '/chatter')")
        _type_argument(parser, nargs='?', help_text="Type of the ROS message (e.g. 'std_msgs/msg/String')")
        add_qos_arguments(parser, 'subscribe', 'sensor_data')
        add_message_output_arguments(parser)
        parser.add_argument('--no-lost-messages', action='store_true',
                            help="Don't report when a message is lost")
        parser.add_argument('--raw', action='store_true', help='Echo the raw binary representation')
        parser.add_argument('--filter', dest='filter_expr', help='Python expression to filter messages that '
                            'are printed. Expression can use Python builtins as well as m (the message).')
        parser.add_argument('--once', action='store_true',
                            help='Print the first message received and then exit.')
        parser.add_argument('--timeout', type=positive_float, help='Exit after the given number of seconds')
        parser.add_argument('--include-message-info', '-i', action='store_true',
                            help='Shows the associated message info.')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the topic's messages as they arrive, until Ctrl-C, --once or --timeout.

        Without a type the topic's own is used, once the topic is in the graph (within the discovery
        grace). An unknown topic, a topic with several types, or a --field or --filter that fails gives
        the error message.
        """
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 topic -h` imports this module.
        from rosidl_runtime_py.utilities import InvalidType, import_type

        printer = MessagePrinter(args)
        topic = expand_topic_name(args.topic_name)
        with DirectNode(args) as direct:
            graph = direct.graph
            if args.message_type is not None:
                type_name = args.message_type
            else:
                direct.wait_until(lambda: topic_types(graph, topic) is not None, NAMED_LOOKUP_GRACE)
                types = topic_types(graph, topic)
                if types is None:
                    print(f'WARNING: topic [{topic}] does not appear to be published yet')
                    hint = unknown_topic(graph, topic).partition(f"'{topic}'")[2]
                    return f'Could not determine the type for the passed topic{hint}'
                if len(types) > 1:
                    return (f"Cannot echo topic '{topic}', as it contains more than one type: "
                            f"[{', '.join(types)}]")
                type_name = types[0]
            try:
                message_class = import_type(type_name, 'msg')
            except InvalidType as error:
                if args.message_type is not None:
                    return f'The passed message type is invalid: {error}'
                return f"The message type '{type_name}' is invalid: {error}"
            qos = choose_qos(args, graph.publishers_info(topic))
            return self._echo(direct, topic, message_class, qos, printer)

    def _echo(self, direct: Any, topic: str, message_class: Any, qos: Any,
              printer: MessagePrinter) -> int | str:
        # Lazy: rclpy and rosidl_runtime_py (yaml) import slowly; `ros2 topic -h` imports this module.
        from rclpy.event_handler import SubscriptionEventCallbacks
        from rclpy.executors import SingleThreadedExecutor
        from rosidl_runtime_py.convert import dump_yaml

        args = printer.args
        state: dict[str, Any] = {'done': False, 'error': None}

        def on_message(message: Any, info: Any = None) -> None:
            if state['done']:
                return
            try:
                if args.raw:
                    text = f'{message}\n---'
                else:
                    if not printer.matches(message):
                        return
                    text = printer.format(message)
                if args.include_message_info and info is not None:
                    details = {key: info[key] for key in MESSAGE_INFO_KEYS if key in info}
                    text = (','.join(str(v) for v in details.values()) + ',' + text if args.csv
                            else dump_yaml(details) + '---\n' + text)
                print(text)
            except RuntimeError as error:
                state['error'] = str(error)
                state['done'] = True
                return
            if args.once:
                state['done'] = True

        def on_lost(info: Any) -> None:
            print(f'A message was lost!!!\n\ttotal count change:{info.total_count_change}'
                  f'\n\ttotal count: {info.total_count}---')

        callbacks = None if args.no_lost_messages else SubscriptionEventCallbacks(message_lost=on_lost)
        callback = ((lambda message, info: on_message(message, info)) if args.include_message_info
                    else on_message)
        try:
            direct.node.create_subscription(message_class, topic, callback, qos,
                                            event_callbacks=callbacks, raw=args.raw)
        except Exception:  # the RMW cannot report lost messages: subscribe without it
            direct.node.create_subscription(message_class, topic, callback, qos, raw=args.raw)
        executor = SingleThreadedExecutor(context=direct.node.context)
        executor.add_node(direct.node)
        deadline = None if args.timeout is None else time.monotonic() + args.timeout
        while not state['done'] and (deadline is None or time.monotonic() < deadline):
            left = 0.1 if deadline is None else deadline - time.monotonic()
            executor.spin_once(timeout_sec=max(0.0, min(0.1, left)))
        executor.remove_node(direct.node)
        sys.stdout.flush()
        return state['error'] or 0
