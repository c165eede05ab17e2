"""Section 4.5 project "Display Camera": the Olive camera's images in an OpenCV window.

Without a display the venv's start-up hook keeps the window functions working and says so in one
line (docs/without-a-display.md); the node is the same either way.
"""

import signal
import sys
import time

import cv2
import rclpy
from cv_bridge import CvBridge, CvBridgeError
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.exceptions import InvalidTopicNameException, ParameterException
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from sensor_msgs.msg import CompressedImage

from olive_camera.frames import FrameWatch, describe

DEFAULT_IMAGE_TOPIC = '/olive/camera/eye/image/compressed'  # the course's camera, also olive_sim's
WINDOW = 'camera'
CHECK_PERIOD = 1.0   # s between two looks at whether images arrive
STALE_AFTER = 2.0    # s without an image: say that they stopped
WARN_EVERY = 2.0     # s between two warnings about images that cannot be shown
WAITING_EVERY = 5.0  # s between two "waiting for" lines


class DisplayCamera(Node):

    def __init__(self) -> None:
        super().__init__('display_camera')
        self.declare_parameter('image_topic', DEFAULT_IMAGE_TOPIC, ParameterDescriptor(
            description='sensor_msgs/msg/CompressedImage topic of the camera.', read_only=True))
        self.image_topic = self.get_parameter('image_topic').value
        # The camera publishes best effort and volatile (`ros2 topic info -v`): a subscription
        # asking for reliable delivery would never be connected to it.
        qos_profile = QoSProfile(
            depth=10,
            durability=QoSDurabilityPolicy.VOLATILE,
            reliability=QoSReliabilityPolicy.BEST_EFFORT)
        self.bridge = CvBridge()
        try:
            self.subscription = self.create_subscription(
                CompressedImage, self.image_topic, self.image_callback, qos_profile)
        except InvalidTopicNameException:
            raise ValueError(f"image_topic '{self.image_topic}' is not a valid topic name") from None
        self.watch = FrameWatch(STALE_AFTER)
        self.timer = self.create_timer(CHECK_PERIOD, self.check_images)

    def image_callback(self, msg: CompressedImage) -> None:
        try:
            image = self.bridge.compressed_imgmsg_to_cv2(msg)
        except CvBridgeError as error:
            self.get_logger().warning(f'image skipped: {error}', throttle_duration_sec=WARN_EVERY)
            return
        if self.watch.arrived(time.monotonic()):
            self.get_logger().info(f"images on {self.image_topic} ({describe(image)}): "
                                   f"showing them in the window '{WINDOW}'")
        cv2.imshow(WINDOW, image)
        cv2.waitKey(1)  # lets the window draw the image

    def check_images(self) -> None:
        state = self.watch.check(time.monotonic())
        if state == 'stopped':
            self.get_logger().warning(f'no image on {self.image_topic} for {STALE_AFTER} s')
        if state is not None:
            self.get_logger().info(
                f'waiting for images on {self.image_topic} '
                f'({self.count_publishers(self.image_topic)} publisher(s) so far)',
                throttle_duration_sec=WAITING_EVERY)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    display_camera = None
    try:
        display_camera = DisplayCamera()
        rclpy.spin(display_camera)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except (ParameterException, ValueError) as error:
        if display_camera is not None:
            raise
        print(f'display_camera: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        # `ros2 launch` passes Ctrl-C on to its nodes, which the terminal has already sent it to:
        # that second one must not interrupt the clean-up.
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        cv2.destroyAllWindows()
        if display_camera is not None:
            display_camera.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
