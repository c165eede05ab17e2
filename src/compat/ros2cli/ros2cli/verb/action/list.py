"""`ros2 action list`: the actions in the graph, with their types or counts."""

import argparse

from ros2cli.graph_listing import print_listing
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class ListVerb(VerbExtension):
    """Output a list of action names."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -t/--show-types, -c/--count-actions and the NodeStrategy options."""
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the action type')
        parser.add_argument('-c', '--count-actions', action='store_true',
                            help='Only display the number of actions discovered')
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the action names (with their types for -t, or only how many there are for -c)."""
        with NodeStrategy(args) as strategy:
            actions = strategy.graph.action_names_and_types()
        return print_listing(actions, args.show_types, args.count_actions)
