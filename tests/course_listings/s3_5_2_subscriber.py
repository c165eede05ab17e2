import rclpy
from rclpy.node import Node
from std_msgs.msg import Int32  # Import the message type

class MySubscriber(Node):
    def __init__(self):
        super().__init__('my_subscriber')  # Specify node name
        self.subscription = self.create_subscription(
            Int32,
            'my_topic',
            self.callback,
            10
        )

    def callback(self, msg):
        self.get_logger().info(f'Received: {msg.data}')

def main(args=None):
    rclpy.init(args=args)
    subscriber = MySubscriber() # Create an instance of the subscriber node class
    rclpy.spin(subscriber) # Spin the node
    subscriber.destroy_node() # Clean up
    rclpy.shutdown()

if __name__ == '__main__':
    main()
