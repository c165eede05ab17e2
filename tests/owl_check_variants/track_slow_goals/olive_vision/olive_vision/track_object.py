"""A student's tracker that sends goals only every 1.5 s: it centres a still ball, a moving one gets away."""

import math
import time

import cv2
import rclpy
from cv_bridge import CvBridge
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from sensor_msgs.msg import CompressedImage, JointState
from std_msgs.msg import Float32
from std_srvs.srv import Trigger

FOV = math.radians(48.66)
GOAL_EVERY = 1.5  # s


class TrackObject(Node):

    def __init__(self):
        super().__init__('track_object')
        self.position = {'pan': 0.0, 'tilt': 0.0}
        self.publishers_ = {servo: self.create_publisher(Float32, f'/olive/servo/{servo}/goal/position', 10)
                            for servo in self.position}
        for servo in self.position:
            client = self.create_client(Trigger, f'/olive/servo/{servo}/setTorqueEnable')
            client.wait_for_service()
            rclpy.spin_until_future_complete(self, client.call_async(Trigger.Request()))
        self.create_subscription(JointState, '/olive/servo/pan/joint', self.pan_callback, 10)
        self.create_subscription(JointState, '/olive/servo/tilt/joint', self.tilt_callback, 10)
        qos_profile = QoSProfile(depth=1, durability=QoSDurabilityPolicy.VOLATILE,
                                 reliability=QoSReliabilityPolicy.BEST_EFFORT)
        self.bridge = CvBridge()
        self.last_goal = 0.0
        self.create_subscription(CompressedImage, '/olive/camera/eye/image/compressed', self.image_callback,
                                 qos_profile)

    def pan_callback(self, msg):
        self.position['pan'] = msg.position[0]

    def tilt_callback(self, msg):
        self.position['tilt'] = msg.position[0]

    def image_callback(self, msg):
        image = self.bridge.compressed_imgmsg_to_cv2(msg)
        hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
        mask = cv2.inRange(hsv, (0, 120, 70), (8, 255, 255))
        mask |= cv2.inRange(hsv, (172, 120, 70), (179, 255, 255))
        moments = cv2.moments(mask, binaryImage=True)
        if moments['m00'] < 40 or time.monotonic() - self.last_goal < GOAL_EVERY:
            return
        self.last_goal = time.monotonic()
        height, width = mask.shape
        focal = (width / 2) / math.tan(FOV / 2)
        right = math.atan((moments['m10'] / moments['m00'] - width / 2) / focal)
        down = math.atan((moments['m01'] / moments['m00'] - height / 2) / focal)
        for servo, goal in (('pan', self.position['pan'] - right), ('tilt', self.position['tilt'] + down)):
            msg = Float32()
            msg.data = goal
            self.publishers_[servo].publish(msg)


def main(args=None):
    rclpy.init(args=args)
    track_object = TrackObject()
    try:
        rclpy.spin(track_object)
    except KeyboardInterrupt:
        pass
    track_object.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
