"""add_two_ints_server: answers `add_two_ints` (example_interfaces/srv/AddTwoInts) with a + b."""

from example_interfaces.srv import AddTwoInts
from owl_common.run import spin_node
from rclpy.node import Node


class AddTwoIntsServer(Node):
    """Serves `add_two_ints`, logging each request."""

    def __init__(self, node_name: str = 'add_two_ints_server') -> None:
        super().__init__(node_name)
        self.service = self.create_service(AddTwoInts, 'add_two_ints', self.add)

    def add(self, request: AddTwoInts.Request, response: AddTwoInts.Response) -> AddTwoInts.Response:
        """response.sum = request.a + request.b, wrapped to int64 as C++ would."""
        self.get_logger().info(f'Incoming request\na: {request.a} b: {request.b}')
        response.sum = wrap_int64(request.a + request.b)
        return response


def wrap_int64(value: int) -> int:
    """The value as a signed 64-bit integer holds it (the sum of two large int64 overflows)."""
    return (value + 2**63) % 2**64 - 2**63


def main(args: list[str] | None = None) -> None:
    """Serve until Ctrl-C."""
    spin_node(AddTwoIntsServer, args)
