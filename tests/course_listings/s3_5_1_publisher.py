import rclpy
from rclpy.node import Node      # Import the node class
from std_msgs.msg import Int32  # Import the message type


class MyPublisher(Node):
    def __init__(self):
        super().__init__('my_publisher') # Specify node name
        # Create publisher
        self.publisher_ = self.create_publisher(Int32, 'my_topic', 10)
        # Create a timer
        self.timer = self.create_timer(1.0, self.callback_function)


    def callback_function(self):
        msg = Int32() # Create an instance of the message type
        msg.data = 7 # Set the message data
        self.publisher_.publish(msg) # Publish the message
        self.get_logger().info('Published: %d' % msg.data)

def main(args=None):
    rclpy.init(args=args)
    publisher = MyPublisher()  # Create an instance of the publisher node class
    rclpy.spin(publisher)  # Spin the node
    publisher.destroy_node()  # Clean up
    rclpy.shutdown()

if __name__ == '__main__':
    main()
