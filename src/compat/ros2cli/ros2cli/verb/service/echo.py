"""`ros2 service echo <service> [type]`: print a service's introspection events as they happen.

A client or server whose introspection is on (rclpy's `configure_introspection`) publishes an
event on `<service>/_service_event` for each request sent or received and each response sent or
received; this verb prints them as `ros2 topic echo` prints messages, with the event type by name.
"""

import argparse
from typing import Any

from owl_common.graph import expand_topic_name

from ros2cli.api.service import _service_argument, visible_services
from ros2cli.api.topic import RECEIVE_DEPTH
from ros2cli.graph_listing import types_of
from ros2cli.node.direct import NAMED_LOOKUP_GRACE, DirectNode
from ros2cli.verb import VerbExtension
from ros2cli.verb.topic.echo import add_message_output_arguments

EVENT_SUFFIX = '/_service_event'
# service_msgs/msg/ServiceEventInfo's event_type constants, by value.
EVENT_TYPE_NAMES = {0: 'REQUEST_SENT', 1: 'REQUEST_RECEIVED', 2: 'RESPONSE_SENT', 3: 'RESPONSE_RECEIVED'}


def event_text(event: Any, args: argparse.Namespace) -> str:
    """One event as printed: YAML with the event type's name, then '---'; or one CSV line for --csv."""
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 service -h` imports this module.
    from rosidl_runtime_py.convert import dump_yaml, message_to_csv, message_to_ordereddict

    truncate = None if args.full_length else args.truncate_length
    if args.csv:
        return message_to_csv(event, truncate_length=truncate, no_arr=args.no_arr, no_str=args.no_str)
    fields = message_to_ordereddict(event, truncate_length=truncate, no_arr=args.no_arr, no_str=args.no_str)
    kind = fields['info']['event_type']
    fields['info']['event_type'] = EVENT_TYPE_NAMES.get(kind, kind)
    return dump_yaml(fields, args.flow_style) + '---'


class EchoVerb(VerbExtension):
    """Echo a service."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the service name, its optional type and the output options (upstream's, no QoS options)."""
        _service_argument(parser, "Name of the ROS service to echo (e.g. '/add_two_ints')")
        parser.add_argument('service_type', nargs='?',
                            help="Type of the ROS service (e.g. 'example_interfaces/srv/AddTwoInts')")
        add_message_output_arguments(parser, with_field=False)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print each event until Ctrl-C; an unknown service or an invalid type is an error.

        Without a type the service's own is used, once it is in the graph (within the discovery
        grace). While nobody publishes events, it says once that introspection may be off.
        """
        # Lazy: these import slowly, and `ros2 service -h` imports this module.
        from owl_common.hints import did_you_mean
        from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
        from rosidl_runtime_py.utilities import InvalidType, import_type

        service = expand_topic_name(args.service_name)
        with DirectNode(args) as direct:
            graph = direct.graph
            type_name = args.service_type
            if type_name is None:
                def types() -> list[str] | None:
                    return types_of(visible_services(graph, True), service)

                direct.wait_until(lambda: types() is not None, NAMED_LOOKUP_GRACE)
                found = types()
                if found is None:
                    known = [name for name, _ in visible_services(graph, False)]
                    return f"Cannot find type for '{service}'{did_you_mean(service, known)}"
                if len(found) > 1:
                    return f"More than one type associated with service '{service}': {', '.join(found)}"
                type_name = found[0]
            try:
                event_class = import_type(type_name, 'srv').Event
            except InvalidType as error:
                return f"The service type '{type_name}' is invalid: {error}"
            topic = service + EVENT_SUFFIX
            # The services_default preset's policies; deeper, so a burst waits while events are printed.
            qos = QoSProfile(depth=RECEIVE_DEPTH, reliability=QoSReliabilityPolicy.RELIABLE,
                             durability=QoSDurabilityPolicy.VOLATILE)
            direct.node.create_subscription(
                event_class, topic, lambda event: print(event_text(event, args), flush=True), qos)
            if graph.count_publishers(topic) < 1:
                print(f"No publishers on topic '{topic}'; is service introspection on the client or server "
                      'enabled?', flush=True)
            while True:
                direct.spin_for(0.1)
