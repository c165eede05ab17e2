"""`ros2 action type`: an action's types."""

import argparse

from ros2cli.api.action import _action_argument
from ros2cli.graph_listing import print_types
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class TypeVerb(VerbExtension):
    """Print a action's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name and the NodeStrategy options."""
        _action_argument(parser, "Name of the ROS action to get type (e.g. '/fibonacci')")
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the action's types one a line; exit code 1 when the action never shows up."""
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: graph.action_names_and_types(), args.action_name)
