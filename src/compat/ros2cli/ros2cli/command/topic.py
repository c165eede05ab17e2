"""`ros2 topic list | info | type | find | echo | pub | hz | bw`."""

import argparse
from typing import Any

from ros2cli.command import VerbCommand
from ros2cli.node.graph import Graph
from ros2cli.verb import VerbExtension


def _include_hidden(args: argparse.Namespace) -> bool:
    return bool(getattr(args, 'include_hidden_topics', False)
                or getattr(args, 'command_include_hidden', False))


def _add_hidden_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--include-hidden-topics', action='store_true', help='Consider hidden topics as well')


def visible_topics(graph: Graph, include_hidden: bool) -> list[list[Any]]:
    """The graph's [name, [type, ...]] topic entries, hidden topics left out unless include_hidden."""
    from owl_common.graph import is_hidden_name
    return [[name, types] for name, types in graph.topic_names_and_types()
            if include_hidden or not is_hidden_name(name)]


def _topic_argument(parser: argparse.ArgumentParser, help_text: str = 'Name of the ROS topic') -> None:
    from ros2cli.completion import topic_completer, with_completer
    with_completer(parser.add_argument('topic_name', help=help_text), topic_completer)


def _type_argument(parser: argparse.ArgumentParser, nargs: str | None = None, help_text: str = '') -> None:
    from ros2cli.completion import message_type_completer, with_completer
    with_completer(parser.add_argument(
        'message_type', nargs=nargs, help=help_text or "Type of the ROS message (e.g. 'std_msgs/msg/String')"
    ), message_type_completer)


def topic_types(graph: Graph, topic: str) -> list[str] | None:
    """The topic's types in the graph, or None while the topic is not (yet) in it."""
    from ros2cli.graph_listing import types_of
    return types_of(graph.topic_names_and_types(), topic)


def unknown_topic(graph: Graph, topic: str) -> str:
    """The error message for a topic that is not in the graph, with a 'did you mean' hint."""
    from owl_common.hints import did_you_mean
    return f"Unknown topic '{topic}'{did_you_mean(topic, [n for n, _ in graph.topic_names_and_types()])}"


class ListVerb(VerbExtension):
    """Output a list of available topics."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the listing options (-t, -c, -v, --include-hidden-topics) and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        add_strategy_arguments(parser)
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the topic type')
        parser.add_argument('-c', '--count-topics', action='store_true',
                            help='Only display the number of topics discovered')
        _add_hidden_argument(parser)
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='List full details about each topic')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the topic names (with their types for -t, or only how many there are for -c).

        -v lists published and subscribed topics instead, each with its number of publishers or
        subscribers.
        """
        from ros2cli.graph_listing import print_listing
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            topics = visible_topics(strategy.graph, _include_hidden(args))
            if args.count_topics:
                print(len(topics))
                return 0
            if args.verbose:
                graph = strategy.graph
                counts = {name: (graph.count_publishers(name), graph.count_subscribers(name))
                          for name, _ in topics}
        if args.verbose:
            for title, index, word in (('Published topics:', 0, 'publisher'),
                                       ('Subscribed topics:', 1, 'subscriber')):
                print(title)
                for name, types in topics:
                    count = counts[name][index]
                    if count:
                        print(f" * {name} [{', '.join(types)}] {count} {word}{'s' if count > 1 else ''}")
                print()
            return 0
        return print_listing(topics, args.show_types, count_only=False)


def endpoint_text(endpoint: dict[str, Any]) -> str:
    """An endpoint as upstream prints it (rclpy's TopicEndpointInfo.__str__)."""
    history = endpoint['history']
    if history == 'KEEP_LAST':
        history = f"KEEP_LAST ({endpoint['depth']})"
    gid = '.'.join(f'{byte:02x}' for byte in endpoint['endpoint_gid'])
    return '\n'.join([
        f"Node name: {endpoint['node_name']}",
        f"Node namespace: {endpoint['node_namespace']}",
        f"Topic type: {endpoint['topic_type']}",
        f"Topic type hash: {endpoint['topic_type_hash']}",
        f"Endpoint type: {endpoint['endpoint_type']}",
        f'GID: {gid}',
        'QoS profile:',
        f"  Reliability: {endpoint['reliability']}",
        f'  History (Depth): {history}',
        f"  Durability: {endpoint['durability']}",
        f"  Lifespan: {endpoint['lifespan']}",
        f"  Deadline: {endpoint['deadline']}",
        f"  Liveliness: {endpoint['liveliness']}",
        f"  Liveliness lease duration: {endpoint['liveliness_lease_duration']}",
    ])


class InfoVerb(VerbExtension):
    """Print information about a topic."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, -v/--verbose and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _topic_argument(parser, 'Name of the ROS topic to get info (e.g. \'/chatter\')')
        parser.add_argument('--verbose', '-v', action='store_true',
                            help='Prints detailed information like the node name, node namespace, topic '
                                 'type, topic type hash, GUID, and QoS Profile of the publishers and '
                                 'subscribers to this topic')
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the topic's type and how many publishers and subscriptions it has (-v: each one's details).

        An unknown topic gives the error message, with a 'did you mean' hint.
        """
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            graph = strategy.graph
            strategy.wait_until(lambda: topic_types(graph, args.topic_name) is not None)
            types = topic_types(graph, args.topic_name)
            if types is None:
                return unknown_topic(graph, args.topic_name)
            type_text = types[0] if len(types) == 1 else str(types)
            end = '\n' if args.verbose else ''
            print(f'Type: {type_text}\n{end}', end='')
            publishers = graph.publishers_info(args.topic_name)
            subscriptions = graph.subscriptions_info(args.topic_name)
        for title, endpoints in (('Publisher count', publishers), ('Subscription count', subscriptions)):
            print(f'{title}: {len(endpoints)}\n{end}', end='')
            if args.verbose:
                for endpoint in endpoints:
                    print(endpoint_text(endpoint), end='\n\n')
        return 0


class TypeVerb(VerbExtension):
    """Print a topic's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, --include-hidden-topics and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _topic_argument(parser, 'Name of the ROS topic to get type (e.g. \'/chatter\')')
        _add_hidden_argument(parser)
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the topic's types one a line; exit code 1 when the topic never shows up (or is hidden)."""
        from ros2cli.graph_listing import print_types
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: visible_topics(graph, _include_hidden(args)),
                               args.topic_name)


class FindVerb(VerbExtension):
    """Output a list of available topics of a given type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the message type, -c/--count-topics, --include-hidden-topics and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _type_argument(parser, help_text='Name of the ROS topic type to filter for '
                       "(e.g. 'std_msgs/msg/String')")
        add_strategy_arguments(parser)
        parser.add_argument('-c', '--count-topics', action='store_true',
                            help='Only display the number of topics discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the topics of that type (or only how many there are for -c)."""
        from ros2cli.graph_listing import print_names_of_type
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            topics = visible_topics(strategy.graph, _include_hidden(args))
        return print_names_of_type(topics, args.message_type, args.count_topics)


class TopicCommand(VerbCommand):
    """Various topic related sub-commands."""

    VERB_GROUP = 'ros2topic.verb'

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the verbs, and --include-hidden-topics as an option of the command itself (as upstream).

        The list, type and find verbs honour it as they do their own --include-hidden-topics.
        """
        parser.add_argument('--include-hidden-topics', dest='command_include_hidden', action='store_true',
                            help='Consider hidden topics as well')
        super().add_arguments(parser, cli_name)


def wait_for_topic_type(direct: Any, topic: str) -> list[str]:
    """The topic's types, once the topic is in the graph; like upstream it waits as long as it takes.

    While it waits it prints a warning, and says on stderr when the name looks mistyped.
    """
    from ros2cli.names import WaitingHint
    from ros2cli.node.direct import NAMED_LOOKUP_GRACE

    types = topic_types(direct.graph, topic)
    if types is None:
        print(f'WARNING: topic [{topic}] does not appear to be published yet')
        hint = WaitingHint(f"topic '{topic}'", topic, NAMED_LOOKUP_GRACE)
        while types is None:
            direct.spin_for(0.1)
            types = topic_types(direct.graph, topic)
            hint.update(lambda: [name for name, _ in direct.graph.topic_names_and_types()])
    return types
