"""Log every number received on random_numbers."""

from owl_common.run import spin_node
from rclpy.node import Node
from std_msgs.msg import Int32


class RandomNumberSubscriber(Node):

    def __init__(self):
        super().__init__('random_number_subscriber')
        self.subscription = self.create_subscription(
            Int32, 'random_numbers', self.random_number_callback, 10)

    def random_number_callback(self, msg: Int32):
        self.get_logger().info(f'Received: {msg.data}')


def main(args=None):
    spin_node(RandomNumberSubscriber, args)


if __name__ == '__main__':
    main()
