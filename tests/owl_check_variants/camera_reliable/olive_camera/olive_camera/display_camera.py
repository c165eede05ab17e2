"""display_camera with the default (reliable) QoS of a depth 10: owl check must fail it."""

import cv2
import rclpy
from cv_bridge import CvBridge
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage


class DisplayCamera(Node):
    def __init__(self):
        super().__init__('display_camera')
        self.subscription = self.create_subscription(
            CompressedImage, '/olive/camera/eye/image/compressed', self.listener_callback, 10
        )
        self.bridge = CvBridge()

    def listener_callback(self, msg):
        cv2.imshow('camera', self.bridge.compressed_imgmsg_to_cv2(msg))
        cv2.waitKey(1)


def main(args=None):
    rclpy.init(args=args)
    node = DisplayCamera()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
