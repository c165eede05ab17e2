"""Section 3.5 exercise: publish 1, 2, 3, ... on random_numbers once a second."""

from owl_common.run import spin_node
from rclpy.node import Node
from std_msgs.msg import Int32


class CounterPublisher(Node):

    def __init__(self):
        super().__init__('counter_publisher')
        self.publisher_ = self.create_publisher(Int32, 'random_numbers', 10)
        self.count = 0
        self.timer = self.create_timer(1.0, self.publish_next)

    def publish_next(self):
        self.count += 1
        self.get_logger().info(f'Publishing: {self.count}')
        self.publisher_.publish(Int32(data=self.count))


def main(args=None):
    spin_node(CounterPublisher, args)


if __name__ == '__main__':
    main()
