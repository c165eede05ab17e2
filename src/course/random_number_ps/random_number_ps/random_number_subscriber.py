"""Log every number received on random_numbers."""

import signal

import rclpy
from rclpy.node import Node
from std_msgs.msg import Int32


class RandomNumberSubscriber(Node):

    def __init__(self) -> None:
        super().__init__('random_number_subscriber')
        self.subscription = self.create_subscription(
            Int32, 'random_numbers', self.random_number_callback, 10)

    def random_number_callback(self, msg: Int32) -> None:
        self.get_logger().info(f'Received: {msg.data}')


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    random_number_subscriber = None
    try:
        random_number_subscriber = RandomNumberSubscriber()
        rclpy.spin(random_number_subscriber)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if random_number_subscriber is not None:
            random_number_subscriber.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
