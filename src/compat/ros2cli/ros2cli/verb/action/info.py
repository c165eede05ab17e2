"""`ros2 action info`: the clients and servers of an action."""

import argparse
import sys

from owl_common.graph import full_node_name
from owl_common.hints import did_you_mean

from ros2cli.api.action import _action_argument, action_types
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class InfoVerb(VerbExtension):
    """Print information about an action."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name, -t/--show-types, -c/--count and the NodeStrategy options."""
        _action_argument(parser, "Name of the ROS action to get info (e.g. '/fibonacci')")
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the action type')
        parser.add_argument('-c', '--count', action='store_true', help='Only display the number of action '
                            'clients and action servers')
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the nodes that are the action's clients and servers (with types for -t, only counts for -c).

        The name must be absolute, else its error message is returned. An action that is not in the
        graph (after the discovery grace) gives empty sections and, when a known name is close, a
        'did you mean' line on stderr.
        """
        if not args.action_name.startswith('/') or args.action_name.endswith('/') or '//' in args.action_name:
            return f"Invalid action name '{args.action_name}': it must be absolute, e.g. '/fibonacci'"
        with NodeStrategy(args) as strategy:
            graph = strategy.graph
            strategy.wait_until(lambda: action_types(graph, args.action_name) is not None)
            # (node's full name, the action's types) for each client and server of the action
            clients: list[tuple[str, list[str]]] = []
            servers: list[tuple[str, list[str]]] = []
            for name, namespace in graph.node_names_and_namespaces():
                node = full_node_name(namespace, name)
                for found, query in ((clients, graph.action_clients_by_node),
                                     (servers, graph.action_servers_by_node)):
                    for action, types in query(name, namespace):
                        if action == args.action_name:
                            found.append((node, types))
            known = [name for name, _ in graph.action_names_and_types()]
        print(f'Action: {args.action_name}')
        for title, entries in (('Action clients', clients), ('Action servers', servers)):
            print(f'{title}: {len(entries)}')
            if not args.count:
                for node, types in sorted(entries):
                    print(f"    {node} [{', '.join(types)}]" if args.show_types else f'    {node}')
        if not clients and not servers:
            hint = did_you_mean(args.action_name, known)
            if hint:
                print(f"No action '{args.action_name}' in the graph{hint}", file=sys.stderr)
        return 0
