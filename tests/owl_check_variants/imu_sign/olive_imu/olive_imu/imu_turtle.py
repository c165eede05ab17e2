"""imu_turtle with the wrong sign of pitch: owl check must fail it."""

import math

import rclpy
from geometry_msgs.msg import Quaternion, Twist
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from sensor_msgs.msg import Imu


class ImuTurtle(Node):
    def __init__(self):
        super().__init__('imu_turtle')
        self.orientation = Quaternion()
        self.subscription = self.create_subscription(
            Imu, '/olive/imu/x1684267976913/imu', self.imu_callback, 10
        )
        self.publisher = self.create_publisher(Twist, '/turtle1/cmd_vel', 10)

    def quaternion_to_euler(self, q):
        roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x**2 + q.y**2))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y**2 + q.z**2))
        return roll, pitch, yaw

    def imu_callback(self, msg):
        self.orientation = msg.orientation
        _roll, pitch, yaw = self.quaternion_to_euler(self.orientation)
        twist = Twist()
        twist.linear.x = -pitch
        twist.angular.z = yaw
        self.publisher.publish(twist)


def main(args=None):
    rclpy.init(args=args)
    node = ImuTurtle()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
