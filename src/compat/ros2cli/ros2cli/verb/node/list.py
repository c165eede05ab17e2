"""`ros2 node list`: the nodes in the graph."""

import argparse
import sys

from ros2cli.api.node import node_names
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension

DUPLICATE_WARNING = ('WARNING: Be aware that there are nodes in the graph that share an exact name, '
                     'which can have unintended side effects.')


class ListVerb(VerbExtension):
    """Output a list of available nodes."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the NodeStrategy options, -a/--all (hidden nodes too) and -c/--count-nodes."""
        add_strategy_arguments(parser)
        parser.add_argument('-a', '--all', action='store_true', help='Display all nodes even hidden ones')
        parser.add_argument('-c', '--count-nodes', action='store_true',
                            help='Only display the number of nodes discovered')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the nodes' full names, sorted, or only how many there are (-c).

        Names that several nodes share are listed each time, after a warning on stderr.
        """
        with NodeStrategy(args) as strategy:
            names = node_names(strategy.graph, args.all)
        if args.count_nodes:
            print(len(names))
            return 0
        if len(set(names)) != len(names):
            print(DUPLICATE_WARNING, file=sys.stderr)
        for name in names:
            print(name)
        return 0
