"""factorial_server: n! for 0 <= n <= 20 (service factorial); anything else answers success=false."""

import signal

import rclpy
from olive_interfaces.srv import Factorial
from rclpy.node import Node

from olive_srvcli.conversions import factorial


class FactorialService(Node):

    def __init__(self) -> None:
        super().__init__('factorial_service')
        self.srv = self.create_service(Factorial, 'factorial', self.factorial_callback)

    def factorial_callback(self, request: Factorial.Request,
                           response: Factorial.Response) -> Factorial.Response:
        self.get_logger().info(f'Incoming request: {request.n}!')
        outcome = factorial(request.n)
        response.success = outcome.ok
        if outcome.ok:
            response.factorial = outcome.value
        else:
            response.message = outcome.error
            self.get_logger().warn(f'Refusing request: {outcome.error}')
        return response


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    factorial_service = None
    try:
        factorial_service = FactorialService()
        rclpy.spin(factorial_service)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if factorial_service is not None:
            factorial_service.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
