"""The service introspection demo: introspection_service and introspection_client.

Both use `add_two_ints` (example_interfaces/srv/AddTwoInts). A string parameter switches each
side's introspection between disabled, metadata and contents at run time; `ros2 service echo
/add_two_ints` then shows what the enabled sides publish on `/add_two_ints/_service_event`.
"""

import rclpy
from example_interfaces.srv import AddTwoInts
from owl_common.run import spin_node
from rcl_interfaces.msg import SetParametersResult
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import qos_profile_system_default
from rclpy.service_introspection import ServiceIntrospectionState

from demo_nodes_py.services.add_two_ints_server import wrap_int64

STATES = {
    'disabled': ServiceIntrospectionState.OFF,
    'metadata': ServiceIntrospectionState.METADATA,
    'contents': ServiceIntrospectionState.CONTENTS,
}
REQUEST_PERIOD = 0.5  # s: the client's pace


def introspection_state(value: object) -> ServiceIntrospectionState | str:
    """The state a parameter value asks for, or why the value is refused."""
    if not isinstance(value, str):
        return 'must be a string'
    if value not in STATES:
        return "must be one of 'disabled', 'metadata', or 'contents'"
    return STATES[value]


class IntrospectionSwitch:
    """The parameter `<side>_configure_introspection` of a node, applied to its service or client."""

    def __init__(self, node: Node, side: str, endpoint: rclpy.service.Service | rclpy.client.Client) -> None:
        self.node = node
        self.endpoint = endpoint
        self.name = f'{side}_configure_introspection'
        node.declare_parameter(self.name, 'disabled')
        node.add_on_set_parameters_callback(self.on_set)

    def on_set(self, parameters: list[Parameter]) -> SetParametersResult:
        """Apply a new value of the parameter; refuse a value that names no state."""
        for parameter in parameters:
            if parameter.name != self.name:
                continue
            state = introspection_state(parameter.value)
            if isinstance(state, str):
                return SetParametersResult(successful=False, reason=state)
            self.endpoint.configure_introspection(self.node.get_clock(), qos_profile_system_default, state)
        return SetParametersResult(successful=True)


class IntrospectionService(Node):
    """add_two_ints served, with `service_configure_introspection`."""

    def __init__(self) -> None:
        super().__init__('introspection_service')
        self.service = self.create_service(AddTwoInts, 'add_two_ints', self.add)
        self.switch = IntrospectionSwitch(self, 'service', self.service)

    def add(self, request: AddTwoInts.Request, response: AddTwoInts.Response) -> AddTwoInts.Response:
        """response.sum = request.a + request.b."""
        self.get_logger().info(f'Incoming request\na: {request.a} b: {request.b}')
        response.sum = wrap_int64(request.a + request.b)
        return response


class IntrospectionClient(Node):
    """Asks add_two_ints for 2 + 3 every REQUEST_PERIOD, one request at a time.

    Its introspection is switched by `client_configure_introspection`.
    """

    def __init__(self) -> None:
        super().__init__('introspection_client')
        self.client = self.create_client(AddTwoInts, 'add_two_ints')
        self.switch = IntrospectionSwitch(self, 'client', self.client)
        self.pending: rclpy.task.Future | None = None
        self.timer = self.create_timer(REQUEST_PERIOD, self.ask)

    def ask(self) -> None:
        """Send 2 + 3 when the server is there and the last answer came."""
        if self.pending is not None and not self.pending.done():
            return
        if not self.client.service_is_ready():
            return
        self.pending = self.client.call_async(AddTwoInts.Request(a=2, b=3))
        self.pending.add_done_callback(self.answered)

    def answered(self, future: rclpy.task.Future) -> None:
        """Log the sum."""
        self.get_logger().info(f'Result of add_two_ints: {future.result().sum}')


def main(args: list[str] | None = None) -> None:
    """demo_nodes_py's `introspection`: the service and the client in one process, until Ctrl-C."""
    spin_node(lambda: [IntrospectionService(), IntrospectionClient()], args)


def service_main(args: list[str] | None = None) -> None:
    """Run introspection_service until Ctrl-C."""
    spin_node(IntrospectionService, args)


def client_main(args: list[str] | None = None) -> None:
    """Run introspection_client until Ctrl-C."""
    spin_node(IntrospectionClient, args)
