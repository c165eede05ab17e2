"""`ros2 node info`: what a node publishes, subscribes to, serves and calls."""

import argparse
import sys
from typing import Any

from owl_common.graph import is_hidden_name, split_node_name
from owl_common.hints import did_you_mean

from ros2cli.api.node import node_names
from ros2cli.completion import node_completer, with_completer
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


def print_section(title: str, names_and_types: list[list[Any]], include_hidden: bool) -> None:
    """Print one section of `node info`: its title, then a `name: types` line per entry.

    Hidden names are left out unless include_hidden; an empty section prints one empty line.
    """
    print(f'  {title}:')
    lines = [f"    {name}: {', '.join(types)}" for name, types in names_and_types
             if include_hidden or not is_hidden_name(name)]
    # An empty section prints one empty line, as upstream does.
    print('\n'.join(lines))


class InfoVerb(VerbExtension):
    """Output information about a node."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the node name, the NodeStrategy options and --include-hidden."""
        with_completer(parser.add_argument('node_name', help='Node name to request information'),
                       node_completer)
        add_strategy_arguments(parser)
        parser.add_argument('--include-hidden', action='store_true', help='Display hidden topics, '
                            'services, and actions as well')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the node's subscribers, publishers, service servers and clients, action servers and clients.

        An unknown node gives the error message (with a 'did you mean' hint). When several nodes share the
        name, the sections are those of one of them, with a warning on stderr.
        """
        with NodeStrategy(args) as strategy:
            graph = strategy.graph
            strategy.wait_until(lambda: args.node_name in node_names(graph, args.include_hidden))
            names = node_names(graph, args.include_hidden)
            count = names.count(args.node_name)
            if count == 0:
                return f"Unable to find node '{args.node_name}'{did_you_mean(args.node_name, names)}"
            if count > 1:
                print(f'There are {count} nodes in the graph with the exact name "{args.node_name}". '
                      'You are seeing information about only one of them.', file=sys.stderr)
            namespace, name = split_node_name(args.node_name)
            sections = [
                ('Subscribers', graph.subscribers_by_node(name, namespace)),
                ('Publishers', graph.publishers_by_node(name, namespace)),
                ('Service Servers', graph.services_by_node(name, namespace)),
                ('Service Clients', graph.clients_by_node(name, namespace)),
                ('Action Servers', graph.action_servers_by_node(name, namespace)),
                ('Action Clients', graph.action_clients_by_node(name, namespace)),
            ]
        print(args.node_name)
        for title, names_and_types in sections:
            print_section(title, names_and_types, args.include_hidden)
        return 0
