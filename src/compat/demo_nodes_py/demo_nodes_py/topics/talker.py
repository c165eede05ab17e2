"""talker: 'Hello World: N' on `chatter` (std_msgs/msg/String) once a second."""

from owl_common.run import spin_node
from rclpy.node import Node
from std_msgs.msg import String

PERIOD = 1.0  # s


class Talker(Node):
    """Publishes a counted greeting every PERIOD and logs each one.

    demo_nodes_cpp's talker differs in the count it starts at, its log line's quotes and its depth.
    """

    def __init__(self, first_count: int = 0, log_line: str = 'Publishing: "{}"', depth: int = 10) -> None:
        super().__init__('talker')
        self.count = first_count
        self.log_line = log_line
        self.publisher = self.create_publisher(String, 'chatter', depth)
        self.timer = self.create_timer(PERIOD, self.publish_greeting)

    def publish_greeting(self) -> None:
        """Publish 'Hello World: <count>' and count on."""
        message = String()
        message.data = f'Hello World: {self.count}'
        self.get_logger().info(self.log_line.format(message.data))
        self.publisher.publish(message)
        self.count += 1


def main(args: list[str] | None = None) -> None:
    """Run the talker until Ctrl-C."""
    spin_node(Talker, args)


