"""A student's factorial client with a name and service of its own, in temp_client's shape."""

import sys

import rclpy
from olive_interfaces.srv import Factorial
from rclpy.node import Node


class FactClient(Node):

    def __init__(self):
        super().__init__('fact_client')
        self.cli = self.create_client(Factorial, 'compute_factorial')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')

    def send_request(self, n):
        future = self.cli.call_async(Factorial.Request(n=n))
        rclpy.spin_until_future_complete(self, future)
        return future.result()


def main(args=None):
    rclpy.init(args=args)
    node = FactClient()
    response = node.send_request(int(sys.argv[1]))
    node.get_logger().info(f'{sys.argv[1]}! = {response.factorial}')
    node.destroy_node()
    rclpy.shutdown()
