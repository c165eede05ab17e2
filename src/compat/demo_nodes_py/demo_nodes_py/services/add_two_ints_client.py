"""add_two_ints_client: asks `add_two_ints` for 2 + 3 once, logs the sum and exits."""

from collections.abc import Callable

import rclpy
from example_interfaces.srv import AddTwoInts
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.task import Future

WAIT_STEP = 1.0  # s between 'service not available' lines


class AddTwoIntsClient(Node):
    """A client of `add_two_ints` that sends one request."""

    def __init__(self, node_name: str = 'add_two_ints_client') -> None:
        super().__init__(node_name)
        self.client = self.create_client(AddTwoInts, 'add_two_ints')

    def wait_for_server(self, say: Callable[[Node, str], None]) -> None:
        """Wait as long as it takes, saying so every WAIT_STEP."""
        while not self.client.wait_for_service(timeout_sec=WAIT_STEP):
            say(self, 'service not available, waiting again...')

    def request(self, a: int, b: int) -> rclpy.task.Future:
        """Send a and b; the future completes with the response."""
        return self.client.call_async(AddTwoInts.Request(a=a, b=b))


def print_line(node: Node, line: str) -> None:
    """How demo_nodes_py's clients say they wait: a plain line on stdout, not a log line."""
    print(line, flush=True)


def log_line(node: Node, line: str) -> None:
    """How demo_nodes_cpp's clients say they wait: an info line of the node's logger."""
    node.get_logger().info(line)


def run_client(args: list[str] | None, wait_for_answer: Callable[[Node, Future], None],
               say_waiting: Callable[[Node, str], None] = print_line) -> None:
    """Wait for the server, ask for 2 + 3, wait for the answer as told, log the sum and exit.

    say_waiting says the server is not there yet. Ctrl-C while waiting ends quietly.
    """
    rclpy.init(args=args)
    node = AddTwoIntsClient()
    try:
        node.wait_for_server(say_waiting)
        future = node.request(2, 3)
        wait_for_answer(node, future)
        if future.done():
            node.get_logger().info(f'Result of add_two_ints: {future.result().sum}')
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


def main(args: list[str] | None = None) -> None:
    """One request, its answer awaited with rclpy.spin_until_future_complete."""
    run_client(args, rclpy.spin_until_future_complete)
