"""A student's display_camera as section 4.5 asks for it: the course's QoS, CvBridge, cv2.imshow.

Not ours (src/course/olive_camera is): what a student writes, to show that the venv's start-up hook keeps
such a program running without a display without a change to it. Its main() has the course's
shape; rclpy.try_shutdown because rclpy's Ctrl-C handler has already shut ROS down (Jazzy's
rclpy.shutdown() would raise "rcl_shutdown already called" there, display or not), and Jazzy's Ctrl-C
may end rclpy.spin with ExternalShutdownException. tests/test_chapter4_walkthrough.py builds it
into a student's olive_camera package; it logs every 30th frame so a test can see it working.
"""

import cv2
import rclpy
from cv_bridge import CvBridge
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from sensor_msgs.msg import CompressedImage


class DisplayCamera(Node):

    def __init__(self):
        super().__init__('display_camera')
        qos_profile = QoSProfile(
            depth=10,
            durability=QoSDurabilityPolicy.VOLATILE,
            reliability=QoSReliabilityPolicy.BEST_EFFORT)
        self.subscription = self.create_subscription(
            CompressedImage, '/olive/camera/eye/image/compressed', self.listener_callback, qos_profile)
        self.bridge = CvBridge()
        self.frames = 0

    def listener_callback(self, msg):
        image = self.bridge.compressed_imgmsg_to_cv2(msg)
        cv2.imshow('Olive Camera', image)
        cv2.waitKey(1)
        self.frames += 1
        if self.frames % 30 == 0:
            self.get_logger().info(f'{self.frames} frames shown')


def main(args=None):
    rclpy.init(args=args)
    display_camera = DisplayCamera()
    try:
        rclpy.spin(display_camera)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    display_camera.destroy_node()
    cv2.destroyAllWindows()
    rclpy.try_shutdown()


if __name__ == '__main__':
    main()
