"""add_two_ints_client_async: add_two_ints_client's request, awaited by spinning until it is done."""

import rclpy
from rclpy.executors import ExternalShutdownException

from demo_nodes_py.services.add_two_ints_client import AddTwoIntsClient


def main(args: list[str] | None = None) -> None:
    """Wait for the server, ask for 2 + 3, spin until the answer is in, log it and exit."""
    rclpy.init(args=args)
    node = AddTwoIntsClient()
    try:
        node.wait_for_server()
        future = node.request(2, 3)
        while rclpy.ok() and not future.done():
            rclpy.spin_once(node, timeout_sec=0.1)
        if future.done():
            node.get_logger().info(f'Result of add_two_ints: {future.result().sum}')
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
