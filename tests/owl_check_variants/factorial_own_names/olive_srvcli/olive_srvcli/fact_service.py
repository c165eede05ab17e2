"""A student's factorial server with a name and service of its own, and a loop that stops one short."""

import rclpy
from olive_interfaces.srv import Factorial
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class FactService(Node):

    def __init__(self):
        super().__init__('fact_service')
        self.srv = self.create_service(Factorial, 'compute_factorial', self.callback)

    def callback(self, request, response):
        result = 1
        for i in range(1, request.n):  # the mistake: range(1, n) leaves n out
            result *= i
        response.success = True
        response.factorial = result
        return response


def main(args=None):
    rclpy.init(args=args)
    node = FactService()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
