"""Section 3.5 exercise: drive a turtlesim turtle with random velocities."""

import random
import signal
import sys

import rclpy
from geometry_msgs.msg import Twist
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import ParameterException
from rclpy.node import Node


def random_twist(rng: random.Random, max_linear: float, max_angular: float) -> Twist:
    """Forward speed in [0, max_linear] m/s and turn rate in [-max_angular, max_angular] rad/s."""
    twist = Twist()
    twist.linear.x = rng.uniform(0.0, max_linear)
    twist.angular.z = rng.uniform(-max_angular, max_angular)
    return twist


def _speed_limit(description: str) -> ParameterDescriptor:
    return ParameterDescriptor(
        description=description,
        floating_point_range=[FloatingPointRange(from_value=0.0, to_value=10.0)])


class TurtleRandomVelocity(Node):

    def __init__(self) -> None:
        super().__init__('turtle_random_velocity')
        self.declare_parameter('max_linear', 2.0, _speed_limit('Largest forward speed, m/s.'))
        self.declare_parameter('max_angular', 2.0, _speed_limit('Largest turn rate, rad/s.'))
        self.declare_parameter('cmd_vel_topic', '/turtle1/cmd_vel', ParameterDescriptor(
            description='Twist topic of the turtle to drive.', read_only=True))
        self.declare_parameter('period', 1.0, ParameterDescriptor(
            description='Seconds between two commands.', read_only=True,
            floating_point_range=[FloatingPointRange(from_value=0.05, to_value=60.0)]))
        topic = self.get_parameter('cmd_vel_topic').value
        self.publisher_ = self.create_publisher(Twist, topic, 10)
        self.rng = random.Random()
        self.timer = self.create_timer(self.get_parameter('period').value, self.publish_velocity)

    def publish_velocity(self) -> None:
        twist = random_twist(
            self.rng, self.get_parameter('max_linear').value, self.get_parameter('max_angular').value)
        self.get_logger().info(
            f'Publishing: linear.x={twist.linear.x:.2f} angular.z={twist.angular.z:.2f}')
        self.publisher_.publish(twist)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    turtle_random_velocity = None
    try:
        turtle_random_velocity = TurtleRandomVelocity()
        rclpy.spin(turtle_random_velocity)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except (ParameterException, ValueError) as error:
        if turtle_random_velocity is not None:
            raise
        print(f'turtle_random_velocity: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if turtle_random_velocity is not None:
            turtle_random_velocity.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
