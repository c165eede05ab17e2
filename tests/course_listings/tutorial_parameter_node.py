# A parameter node shaped like the official ROS 2 tutorials' Python nodes: no try/except around
# rclpy.spin; it sets its parameter back each time it has logged it.
import rclpy
import rclpy.node


class ParameterNode(rclpy.node.Node):
    def __init__(self):
        super().__init__('parameter_node')
        self.declare_parameter('my_parameter', 'world')
        self.timer = self.create_timer(0.5, self.timer_callback)

    def timer_callback(self):
        my_param = self.get_parameter('my_parameter').get_parameter_value().string_value
        self.get_logger().info('Hello %s!' % my_param)
        my_new_param = rclpy.parameter.Parameter('my_parameter', rclpy.Parameter.Type.STRING, 'world')
        self.set_parameters([my_new_param])


def main():
    rclpy.init()
    node = ParameterNode()
    rclpy.spin(node)


if __name__ == '__main__':
    main()
