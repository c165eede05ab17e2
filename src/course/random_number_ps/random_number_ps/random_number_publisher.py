"""Publish a random integer between lower_limit and upper_limit on random_numbers once a second."""

import random
import signal
import sys

import rclpy
from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult
from rclpy.exceptions import ParameterException
from rclpy.node import Node
from rclpy.parameter import Parameter
from std_msgs.msg import Int32

from random_number_ps.limits import check_limits


class RandomNumberPublisher(Node):

    def __init__(self) -> None:
        super().__init__('random_number_publisher')
        self.declare_parameter(
            'upper_limit', 100,
            ParameterDescriptor(description='Largest number published (inclusive).'))
        self.declare_parameter(
            'lower_limit', 1,
            ParameterDescriptor(description='Smallest number published (inclusive).'))
        reason = check_limits(self._limit('lower_limit'), self._limit('upper_limit'))
        if reason:
            raise ValueError(reason)
        self.add_on_set_parameters_callback(self._check_new_limits)
        self.publisher_ = self.create_publisher(Int32, 'random_numbers', 10)
        self.timer = self.create_timer(1.0, self.publish_random_number)

    def _limit(self, name: str) -> int:
        return self.get_parameter(name).get_parameter_value().integer_value

    def _check_new_limits(self, parameters: list[Parameter]) -> SetParametersResult:
        # The declared integer type already refuses other types; this guards the pair.
        new = {p.name: p.value for p in parameters}
        lower = new.get('lower_limit', self._limit('lower_limit'))
        upper = new.get('upper_limit', self._limit('upper_limit'))
        reason = check_limits(lower, upper)
        return SetParametersResult(successful=reason is None, reason=reason or '')

    def publish_random_number(self) -> None:
        random_number = random.randint(self._limit('lower_limit'), self._limit('upper_limit'))
        self.get_logger().info(f'Publishing: {random_number}')
        msg = Int32()
        msg.data = random_number
        self.publisher_.publish(msg)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    random_number_publisher = None
    try:
        random_number_publisher = RandomNumberPublisher()
        rclpy.spin(random_number_publisher)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except (ParameterException, ValueError) as error:
        if random_number_publisher is not None:
            raise
        print(f'random_number_publisher: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if random_number_publisher is not None:
            random_number_publisher.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
