"""Section 3.5 exercise: drive a turtlesim turtle with random velocities."""

import random

from geometry_msgs.msg import Twist
from owl_common.run import spin_node
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
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

    def __init__(self):
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

    def publish_velocity(self):
        twist = random_twist(
            self.rng, self.get_parameter('max_linear').value, self.get_parameter('max_angular').value)
        self.get_logger().info(
            f'Publishing: linear.x={twist.linear.x:.2f} angular.z={twist.angular.z:.2f}')
        self.publisher_.publish(twist)


def main(args=None):
    spin_node(TurtleRandomVelocity, args)


if __name__ == '__main__':
    main()
