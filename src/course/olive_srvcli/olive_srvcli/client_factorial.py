"""factorial_client N: ask the factorial service for N!."""

import sys

import rclpy
from olive_interfaces.srv import Factorial
from rclpy.node import Node

from olive_srvcli.command_line import argument_or_exit, integer_argument


class FactorialClient(Node):

    def __init__(self) -> None:
        super().__init__('factorial_client')
        self.cli = self.create_client(Factorial, 'factorial')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')
        self.req = Factorial.Request()

    def send_request(self, n: int) -> Factorial.Response:
        self.req.n = n
        self.future = self.cli.call_async(self.req)
        rclpy.spin_until_future_complete(self, self.future)
        return self.future.result()


def main(args: list[str] | None = None) -> None:
    n = argument_or_exit(integer_argument, '<n>', args)  # a bad one: one line, exit code 2
    rclpy.init(args=args)
    factorial_client = None
    try:
        factorial_client = FactorialClient()  # waits for the server
        response = factorial_client.send_request(n)
        if not response.success:
            factorial_client.get_logger().error(f'The server refused: {response.message}')
            sys.exit(1)
        factorial_client.get_logger().info(f'The factorial of {n} is {response.factorial}')
    except KeyboardInterrupt:
        pass  # Ctrl-C while it waits for the server
    finally:
        if factorial_client is not None:
            factorial_client.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
