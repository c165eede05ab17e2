"""Section 3.5 exercise: publish 1, 2, 3, ... on random_numbers once a second."""

import signal

import rclpy
from rclpy.node import Node
from std_msgs.msg import Int32


class CounterPublisher(Node):

    def __init__(self) -> None:
        super().__init__('counter_publisher')
        self.publisher_ = self.create_publisher(Int32, 'random_numbers', 10)
        self.count = 0
        self.timer = self.create_timer(1.0, self.publish_next)

    def publish_next(self) -> None:
        self.count += 1
        self.get_logger().info(f'Publishing: {self.count}')
        self.publisher_.publish(Int32(data=self.count))


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    counter_publisher = None
    try:
        counter_publisher = CounterPublisher()
        rclpy.spin(counter_publisher)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if counter_publisher is not None:
            counter_publisher.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
