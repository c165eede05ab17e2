"""add_two_ints_client_async: add_two_ints_client's request, awaited by spinning until it is done."""

import rclpy
from rclpy.node import Node
from rclpy.task import Future

from demo_nodes_py.services.add_two_ints_client import run_client


def spin_until_done(node: Node, future: Future) -> None:
    """Spin the node until the future is done or ROS shuts down."""
    while rclpy.ok() and not future.done():
        rclpy.spin_once(node, timeout_sec=0.1)


def main(args: list[str] | None = None) -> None:
    """One request, its answer awaited with a spin_once loop."""
    run_client(args, spin_until_done)
