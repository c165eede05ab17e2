"""`ros2 service info`: a service's type, and how many clients and servers it has."""

import argparse

from owl_common.hints import did_you_mean

from ros2cli.api.service import _include_hidden, _service_argument, visible_services
from ros2cli.graph_listing import types_of
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class InfoVerb(VerbExtension):
    """Print information about a service."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name and the NodeStrategy options (hidden services: the command's option)."""
        _service_argument(parser, "Name of the ROS service to get info (e.g. '/add_two_ints')")
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print `Type:`, `Clients count:` and `Services count:`; an unknown service is an error."""
        with NodeStrategy(args) as strategy:
            graph = strategy.graph

            def types() -> list[str] | None:
                return types_of(visible_services(graph, _include_hidden(args)), args.service_name)

            strategy.wait_until(lambda: types() is not None)
            found = types()
            if found is None:
                known = [name for name, _ in visible_services(graph, _include_hidden(args))]
                return f"Unknown service '{args.service_name}'{did_you_mean(args.service_name, known)}"
            clients = graph.count_clients(args.service_name)
            servers = graph.count_services(args.service_name)
        print(f'Type: {found[0] if len(found) == 1 else found}')
        print(f'Clients count: {clients}')
        print(f'Services count: {servers}')
        return 0
