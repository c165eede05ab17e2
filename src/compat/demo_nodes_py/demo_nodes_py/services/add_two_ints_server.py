"""add_two_ints_server: answers `add_two_ints` (example_interfaces/srv/AddTwoInts) with a + b."""

import rclpy
from example_interfaces.srv import AddTwoInts
from owl_common.run import spin_node
from rclpy.node import Node

ONE_SHOT_DELAY = 0.1  # s from the first answer to the shutdown, time for the answer to leave


class AddTwoIntsServer(Node):
    """Serves `add_two_ints`, logging each request.

    With with_one_shot (demo_nodes_cpp's server has it, demo_nodes_py's not) the bool parameter
    `one_shot` makes the server shut down once it has answered a request.
    """

    def __init__(self, node_name: str = 'add_two_ints_server', with_one_shot: bool = False) -> None:
        super().__init__(node_name)
        self.one_shot = with_one_shot and self.declare_parameter('one_shot', False).value
        self.service = self.create_service(AddTwoInts, 'add_two_ints', self.add)

    def add(self, request: AddTwoInts.Request, response: AddTwoInts.Response) -> AddTwoInts.Response:
        """response.sum = request.a + request.b, wrapped to int64 as C++ would."""
        self.get_logger().info(f'Incoming request\na: {request.a} b: {request.b}')
        response.sum = wrap_int64(request.a + request.b)
        if self.one_shot:
            self.shutdown_timer = self.create_timer(ONE_SHOT_DELAY, self.shut_down)
        return response

    def shut_down(self) -> None:
        """End the process's spin: the one request of a one_shot server has its answer."""
        rclpy.try_shutdown(context=self.context)


def wrap_int64(value: int) -> int:
    """The value as a signed 64-bit integer holds it (the sum of two large int64 overflows)."""
    return (value + 2**63) % 2**64 - 2**63


def main(args: list[str] | None = None) -> None:
    """Serve until Ctrl-C."""
    spin_node(AddTwoIntsServer, args)
