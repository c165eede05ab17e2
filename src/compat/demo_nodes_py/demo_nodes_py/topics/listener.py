"""listener: logs each message on `chatter` (std_msgs/msg/String)."""

from owl_common.run import spin_node
from rclpy.node import Node
from std_msgs.msg import String


class Listener(Node):
    """Subscribes to `chatter` and logs 'I heard: [<data>]' for each message."""

    def __init__(self) -> None:
        super().__init__('listener')
        self.subscription = self.create_subscription(String, 'chatter', self.heard, 10)

    def heard(self, message: String) -> None:
        """Log what came in."""
        self.get_logger().info(f'I heard: [{message.data}]')


def main(args: list[str] | None = None) -> None:
    """Run the listener until Ctrl-C."""
    spin_node(Listener, args)
