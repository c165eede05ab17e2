"""`ros2 topic info`: a topic's type, publishers and subscriptions (-v: each one's QoS)."""

import argparse
from typing import Any

from ros2cli.api.topic import _topic_argument, topic_types, unknown_topic
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


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
