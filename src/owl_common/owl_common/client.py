"""One-shot command-line service clients, shaped like the course's temp_client."""

import math
import sys
from collections.abc import Callable
from typing import Any

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.utilities import remove_ros_args

from owl_common.run import begin_cleanup


class UsageError(Exception):
    """The command line cannot become a request; the message says why."""


class OneShotClient(Node):
    """A node with one service client that waits for its server, then makes one call."""

    def __init__(self, node_name: str, srv_type: Any, srv_name: str):
        super().__init__(node_name)
        self.cli = self.create_client(srv_type, srv_name)

    def send_request(self, request: Any) -> Any:
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')
        future = self.cli.call_async(request)
        rclpy.spin_until_future_complete(self, future)
        return future.result()


def number_argument(argv: list[str], what: str, kind: type = float) -> Any:
    """The single command-line argument as a finite number of the given kind."""
    if len(argv) != 1:
        raise UsageError(f'expected exactly one argument, {what}; got {len(argv)}')
    text = argv[0]
    try:
        value = kind(text)
    except ValueError:
        article = 'an integer' if kind is int else 'a number'
        raise UsageError(f"'{text}' is not {article}") from None
    if kind is float and not math.isfinite(value):
        raise UsageError(f"'{text}' is not a finite number")
    return value


def run_client(
    make_node: Callable[[], OneShotClient],
    request_from_argv: Callable[[list[str]], Any],
    report: Callable[[OneShotClient, Any, Any], int],
    usage: str,
    args: list[str] | None = None,
) -> None:
    """Build the request from argv, call the service once, report, exit with report's code.

    A bad command line prints one line and exits with code 2 before any ROS work starts.
    Ctrl-C while waiting for the server exits quietly with code 0.
    """
    argv = remove_ros_args(args=sys.argv if args is None else args)
    program = argv[0].rsplit('/', 1)[-1] if argv else 'client'
    try:
        request = request_from_argv(argv[1:])
    except UsageError as error:
        print(f'{program}: error: {error} (usage: {program} {usage})', file=sys.stderr)
        sys.exit(2)
    rclpy.init(args=args)
    node = None
    code = 0
    try:
        node = make_node()
        response = node.send_request(request)
        code = report(node, request, response)
    except (KeyboardInterrupt, ExternalShutdownException):
        code = 0
    finally:
        begin_cleanup()
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    sys.exit(code)
