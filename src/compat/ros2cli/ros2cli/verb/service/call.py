"""`ros2 service call`: call a service with a request given as YAML, once or at a rate."""

import argparse
import time
from typing import TYPE_CHECKING

from owl_common.graph import expand_topic_name

from ros2cli.api.service import _service_argument
from ros2cli.api.topic import add_values_arguments, read_values
from ros2cli.completion import service_type_completer, with_completer
from ros2cli.names import WaitingHint
from ros2cli.node.direct import NAMED_LOOKUP_GRACE, tear_down
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # rclpy is imported where it is used: `ros2 service -h` imports this module
    from rclpy.client import Client
    from rclpy.node import Node


class CallVerb(VerbExtension):
    """Call a service."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name and type, the request's YAML values (or --stdin) and -r/--rate."""
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
        # Lazy: rclpy and rosidl_runtime_py (yaml) import slowly; `ros2 service -h` imports this module.
        import rclpy
        from rclpy.node import Node
        from rosidl_runtime_py.set_message import FieldError, set_message_fields
        from rosidl_runtime_py.utilities import InvalidType, import_type, split_type

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
    hint = WaitingHint(f"server for service '{service}'", service, NAMED_LOOKUP_GRACE)
    while not client.wait_for_service(timeout_sec=0.5):
        hint.update(lambda: [name for name, _ in node.get_service_names_and_types()])
