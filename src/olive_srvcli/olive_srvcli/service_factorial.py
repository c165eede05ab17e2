"""factorial_server: n! for 0 <= n <= 20 (service factorial); anything else answers success=false."""

from olive_interfaces.srv import Factorial
from owl_common.run import spin_node
from rclpy.node import Node

from olive_srvcli.conversions import factorial


class FactorialService(Node):

    def __init__(self):
        super().__init__('factorial_service')
        self.srv = self.create_service(Factorial, 'factorial', self.factorial_callback)

    def factorial_callback(self, request, response):
        self.get_logger().info(f'Incoming request: {request.n}!')
        outcome = factorial(request.n)
        response.success = outcome.ok
        if outcome.ok:
            response.factorial = outcome.value
        else:
            response.message = outcome.error
            self.get_logger().warn(f'Refusing request: {outcome.error}')
        return response


def main(args=None):
    spin_node(FactorialService, args)


if __name__ == '__main__':
    main()
