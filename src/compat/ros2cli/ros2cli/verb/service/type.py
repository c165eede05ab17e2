"""`ros2 service type`: a service's types."""

import argparse

from ros2cli.api.service import _service_argument
from ros2cli.graph_listing import print_types
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class TypeVerb(VerbExtension):
    """Output a service's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name and the NodeStrategy options."""
        _service_argument(parser, "Name of the ROS service to get type (e.g. '/add_two_ints')")
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the service's types one a line; exit code 1 when the service never shows up."""
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: graph.service_names_and_types(), args.service_name)
