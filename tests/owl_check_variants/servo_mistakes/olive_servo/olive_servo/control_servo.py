"""control_servo that never enables the torque: owl check must fail it."""

import math

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from std_msgs.msg import Float32


class ControlServo(Node):
    def __init__(self):
        super().__init__('control_servo')
        self.publisher = self.create_publisher(Float32, '/olive/servo/pan/goal/position', 10)
        self.x = 0.0
        self.timer = self.create_timer(0.01, self.publish_goal)

    def publish_goal(self):
        self.publisher.publish(Float32(data=math.sin(self.x)))
        self.x += 0.01


def main(args=None):
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    node = ControlServo()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
