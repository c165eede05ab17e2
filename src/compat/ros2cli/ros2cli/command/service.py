"""`ros2 service list | type | find | call`."""

import argparse
import time
from typing import TYPE_CHECKING, Any

from ros2cli.command import VerbCommand
from ros2cli.node.graph import Graph
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # rclpy is imported where it is used: `ros2 -h` imports this module
    from rclpy.client import Client
    from rclpy.node import Node


def _include_hidden(args: argparse.Namespace) -> bool:
    return bool(getattr(args, 'include_hidden_services', False)
                or getattr(args, 'command_include_hidden', False))


def _add_hidden_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--include-hidden-services', action='store_true',
                        help='Consider hidden services as well')


def visible_services(graph: Graph, include_hidden: bool) -> list[list[Any]]:
    """The graph's [name, [type, ...]] service entries, hidden services left out unless include_hidden."""
    from owl_common.graph import is_hidden_name
    return [[name, types] for name, types in graph.service_names_and_types()
            if include_hidden or not is_hidden_name(name)]


def _service_argument(parser: argparse.ArgumentParser, help_text: str) -> None:
    from ros2cli.completion import service_completer, with_completer
    with_completer(parser.add_argument('service_name', help=help_text), service_completer)


class ListVerb(VerbExtension):
    """Output a list of available services."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -t/--show-types, -c/--count-services, --include-hidden-services and NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        add_strategy_arguments(parser)
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the service type')
        parser.add_argument('-c', '--count-services', action='store_true',
                            help='Only display the number of services discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the service names (with their types for -t, or only how many there are for -c)."""
        from ros2cli.graph_listing import print_listing
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            services = visible_services(strategy.graph, _include_hidden(args))
        return print_listing(services, args.show_types, args.count_services)


class TypeVerb(VerbExtension):
    """Output a service's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _service_argument(parser, "Name of the ROS service to get type (e.g. '/add_two_ints')")
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the service's types one a line; exit code 1 when the service never shows up."""
        from ros2cli.graph_listing import print_types
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: graph.service_names_and_types(), args.service_name)


class FindVerb(VerbExtension):
    """Output a list of available services of a given type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service type, -c/--count-services, --include-hidden-services and NodeStrategy options."""
        from ros2cli.completion import service_type_completer, with_completer
        from ros2cli.node.strategy import add_strategy_arguments
        with_completer(parser.add_argument('service_type', help="Name of the ROS service type to filter for "
                                           "(e.g. 'rcl_interfaces/srv/ListParameters')"),
                       service_type_completer)
        add_strategy_arguments(parser)
        parser.add_argument('-c', '--count-services', action='store_true',
                            help='Only display the number of services discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the services of that type (or only how many there are for -c)."""
        from ros2cli.graph_listing import print_names_of_type
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            services = visible_services(strategy.graph, _include_hidden(args))
        return print_names_of_type(services, args.service_type, args.count_services)


class CallVerb(VerbExtension):
    """Call a service."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name and type, the request's YAML values (or --stdin) and -r/--rate."""
        from ros2cli.api.topic import add_values_arguments
        from ros2cli.completion import service_type_completer, with_completer
        _service_argument(parser, "Name of the ROS service to call to (e.g. '/add_two_ints')")
        with_completer(parser.add_argument('service_type',
                                           help="Type of the ROS service (e.g. 'std_srvs/srv/Empty')"),
                       service_type_completer)
        add_values_arguments(parser, 'service request', 'a: 1, b: 2')
        parser.add_argument('-r', '--rate', metavar='N', type=float,
                            help='Repeat the call at a specific rate in Hz')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Call the service with the request made of the YAML values and print the response.

        It waits for the server as long as it takes; with -r it calls again at that rate until Ctrl-C. An
        invalid rate, service type or request field is returned as the error message.
        """
        import rclpy
        from owl_common.graph import expand_topic_name
        from rclpy.node import Node
        from rosidl_runtime_py.set_message import FieldError, set_message_fields
        from rosidl_runtime_py.utilities import InvalidType, import_type, split_type

        from ros2cli.api.topic import read_values
        from ros2cli.node.direct import tear_down

        if args.rate is not None and args.rate <= 0:
            return 'rate must be greater than zero'
        try:
            service_class = import_type(args.service_type, 'srv')
        except InvalidType as error:
            return f'The passed service type is invalid: {error}'
        values = read_values(args, 'field')
        try:
            request = service_class.Request()
            set_message_fields(request, values)
        except FieldError as error:
            return f'Failed to populate field: {error}'
        package, _, name = split_type(args.service_type, 'srv')

        rclpy.init(args=[])
        node = Node(f'_ros2cli_requester_{package}_{name}', start_parameter_services=False)
        try:
            client = node.create_client(service_class, expand_topic_name(args.service_name))
            if not client.service_is_ready():
                print('waiting for service to become available...')
                wait_for_server(node, client, expand_topic_name(args.service_name))
            period = None if args.rate is None else 1.0 / args.rate
            while True:
                started = time.monotonic()
                print(f'requester: making request: {request!r}\n')
                future = client.call_async(request)
                rclpy.spin_until_future_complete(node, future)
                if future.exception() is not None:
                    return f'Exception while calling service: {future.exception()!r}'
                print(f'response:\n{future.result()!r}\n')
                if period is None:
                    return 0
                time.sleep(max(0.0, started + period - time.monotonic()))
        finally:
            tear_down(node)


def wait_for_server(node: 'Node', client: 'Client', service: str) -> None:
    """Wait as upstream does (forever), but say when the name looks mistyped."""
    from ros2cli.names import WaitingHint
    from ros2cli.node.direct import NAMED_LOOKUP_GRACE

    hint = WaitingHint(f"server for service '{service}'", service, NAMED_LOOKUP_GRACE)
    while not client.wait_for_service(timeout_sec=0.5):
        hint.update(lambda: [name for name, _ in node.get_service_names_and_types()])


class ServiceCommand(VerbCommand):
    """Various service related sub-commands."""

    VERB_GROUP = 'ros2service.verb'
