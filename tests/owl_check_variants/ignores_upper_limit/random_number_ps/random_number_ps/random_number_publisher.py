"""random_number_publisher that declares upper_limit but never reads it: owl check must fail it."""

import random

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Int32


class RandomNumberPublisher(Node):
    def __init__(self):
        super().__init__('random_number_publisher')
        self.declare_parameter('upper_limit', 100)
        self.publisher_ = self.create_publisher(Int32, 'random_numbers', 10)
        self.timer = self.create_timer(1.0, self.publish_random_number)

    def publish_random_number(self):
        random_number = random.randint(1, 100)
        self.get_logger().info(f'Publishing: {random_number}')
        self.publisher_.publish(Int32(data=random_number))


def main(args=None):
    rclpy.init(args=args)
    node = RandomNumberPublisher()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
