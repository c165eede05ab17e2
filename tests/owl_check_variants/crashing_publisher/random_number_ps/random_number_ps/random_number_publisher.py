"""random_number_publisher whose second callback raises: owl check must show its last lines."""

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Int32


class RandomNumberPublisher(Node):
    def __init__(self):
        super().__init__('random_number_publisher')
        self.publisher_ = self.create_publisher(Int32, 'random_numbers', 10)
        self.timer = self.create_timer(1.0, self.publish_random_number)
        self.count = 0

    def publish_random_number(self):
        self.count += 1
        self.publisher_.publish(Int32(data=100 // (2 - self.count)))


def main(args=None):
    rclpy.init(args=args)
    node = RandomNumberPublisher()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
