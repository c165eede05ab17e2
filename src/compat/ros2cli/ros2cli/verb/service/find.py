"""`ros2 service find`: the services of a given type."""

import argparse

from ros2cli.api.service import _add_hidden_argument, _include_hidden, visible_services
from ros2cli.completion import service_type_completer, with_completer
from ros2cli.graph_listing import print_names_of_type
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class FindVerb(VerbExtension):
    """Output a list of available services of a given type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service type, -c/--count-services, --include-hidden-services and NodeStrategy options."""
        with_completer(parser.add_argument('service_type', help="Name of the ROS service type to filter for "
                                           "(e.g. 'rcl_interfaces/srv/ListParameters')"),
                       service_type_completer)
        add_strategy_arguments(parser)
        parser.add_argument('-c', '--count-services', action='store_true',
                            help='Only display the number of services discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the services of that type (or only how many there are for -c)."""
        with NodeStrategy(args) as strategy:
            services = visible_services(strategy.graph, _include_hidden(args))
        return print_names_of_type(services, args.service_type, args.count_services)
