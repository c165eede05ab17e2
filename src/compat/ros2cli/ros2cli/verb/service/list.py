"""`ros2 service list`: the services in the graph, with their types or counts."""

import argparse

from ros2cli.api.service import _add_hidden_argument, _include_hidden, visible_services
from ros2cli.graph_listing import print_listing
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class ListVerb(VerbExtension):
    """Output a list of available services."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -t/--show-types, -c/--count-services, --include-hidden-services and NodeStrategy options."""
        add_strategy_arguments(parser)
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the service type')
        parser.add_argument('-c', '--count-services', action='store_true',
                            help='Only display the number of services discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the service names (with their types for -t, or only how many there are for -c)."""
        with NodeStrategy(args) as strategy:
            services = visible_services(strategy.graph, _include_hidden(args))
        return print_listing(services, args.show_types, args.count_services)
