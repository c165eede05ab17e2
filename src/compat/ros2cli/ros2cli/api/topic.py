"""What the verbs of `ros2 topic` share (upstream's ros2topic.api): topic lookups and common options."""

import argparse
import sys
from typing import TYPE_CHECKING, Any

from owl_common.graph import is_hidden_name
from owl_common.hints import did_you_mean

from ros2cli.completion import message_type_completer, topic_completer, with_completer
from ros2cli.graph_listing import types_of
from ros2cli.names import WaitingHint
from ros2cli.node.direct import NAMED_LOOKUP_GRACE
from ros2cli.node.graph import Graph

if TYPE_CHECKING:  # rclpy is imported where it is used: `ros2 topic -h` imports this module
    from rclpy.qos import QoSProfile

# The receive queue of echo, hz and bw: a burst that arrives while a message is being handled
# waits instead of being dropped.
RECEIVE_DEPTH = 1000


def _include_hidden(args: argparse.Namespace) -> bool:
    return bool(getattr(args, 'include_hidden_topics', False)
                or getattr(args, 'command_include_hidden', False))


def _add_hidden_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--include-hidden-topics', action='store_true', help='Consider hidden topics as well')


def visible_topics(graph: Graph, include_hidden: bool) -> list[list[Any]]:
    """The graph's [name, [type, ...]] topic entries, hidden topics left out unless include_hidden."""
    return [[name, types] for name, types in graph.topic_names_and_types()
            if include_hidden or not is_hidden_name(name)]


def _topic_argument(parser: argparse.ArgumentParser, help_text: str = 'Name of the ROS topic') -> None:
    with_completer(parser.add_argument('topic_name', help=help_text), topic_completer)


def _type_argument(parser: argparse.ArgumentParser, nargs: str | None = None, help_text: str = '') -> None:
    with_completer(parser.add_argument(
        'message_type', nargs=nargs, help=help_text or "Type of the ROS message (e.g. 'std_msgs/msg/String')"
    ), message_type_completer)


def topic_types(graph: Graph, topic: str) -> list[str] | None:
    """The topic's types in the graph, or None while the topic is not (yet) in it."""
    return types_of(graph.topic_names_and_types(), topic)


def unknown_topic(graph: Graph, topic: str) -> str:
    """The error message for a topic that is not in the graph, with a 'did you mean' hint."""
    return f"Unknown topic '{topic}'{did_you_mean(topic, [n for n, _ in graph.topic_names_and_types()])}"


def wait_for_topic_type(direct: Any, topic: str) -> list[str]:
    """The topic's types, once the topic is in the graph; like upstream it waits as long as it takes.

    While it waits it prints a warning, and says on stderr when the name looks mistyped.
    """
    types = topic_types(direct.graph, topic)
    if types is None:
        print(f'WARNING: topic [{topic}] does not appear to be published yet')
        hint = WaitingHint(f"topic '{topic}'", topic, NAMED_LOOKUP_GRACE)
        while types is None:
            direct.spin_for(0.1)
            types = topic_types(direct.graph, topic)
            hint.update(lambda: [name for name, _ in direct.graph.topic_names_and_types()])
    return types


def positive_float(text: str) -> float:
    """An argparse type: the text as a float, ArgumentTypeError unless it is above zero."""
    value = float(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f'{text} is not a positive number')
    return value


def non_negative_int(text: str) -> int:
    """An argparse type: the text as an int, ArgumentTypeError when it is below zero."""
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f'{text} is negative; give 0 or more')
    return value


def positive_int(text: str) -> int:
    """An argparse type: the text as an int, ArgumentTypeError unless it is above zero."""
    value = int(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f'{text} is not a positive integer')
    return value


def receive_profile() -> 'QoSProfile':
    """sensor_data's policies (best effort: hears every publisher) with room for bursts."""
    # Lazy: rclpy is slow to import, and `ros2 topic -h` imports this module.
    from rclpy.qos import QoSProfile, qos_profile_sensor_data

    return QoSProfile(history=qos_profile_sensor_data.history, depth=RECEIVE_DEPTH,
                      reliability=qos_profile_sensor_data.reliability,
                      durability=qos_profile_sensor_data.durability)


def read_values(args: argparse.Namespace, kind: str) -> Any:
    """The YAML values of the positional argument or --stdin, parsed; RuntimeError when malformed."""
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 topic -h` imports this module.
    from rosidl_runtime_py.set_message import FieldError, parse_yaml
    text = sys.stdin.read() if getattr(args, 'stdin', False) else (args.values or '{}')
    try:
        return parse_yaml(text)
    except FieldError as error:
        raise RuntimeError(f'Failed to populate {kind}: {error}') from None


def add_values_arguments(parser: argparse.ArgumentParser, what: str, example: str) -> None:
    """Add the YAML values (positional) or --stdin; `what` and `example` go into their help texts."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument('values', nargs='?', default='{}',
                       help=f"Values to fill the {what} with in YAML format (e.g. '{example}'), "
                            f'otherwise the {what} will be published with default values')
    group.add_argument('--stdin', action='store_true', help=f'Read {what} values from stdin.')
