"""Section 4.6 project "Use Object Tracking": the pan/tilt head keeps a red ball in the picture's middle."""

import math
import signal
import sys
import time
from collections.abc import Callable

import rclpy
from cv_bridge import CvBridge, CvBridgeError
from olive_servo.bound_parameters import BoundParameters
from olive_servo.goals import SineGoal, clamp
from olive_servo.torque import ServoTorque, TorqueError
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import InvalidTopicNameException, ParameterException
from rclpy.node import Node
from rclpy.qos import QoSDurabilityPolicy, QoSProfile, QoSReliabilityPolicy
from rclpy.time import Time
from rclpy.timer import Timer
from sensor_msgs.msg import CompressedImage, JointState
from std_msgs.msg import Float32

from olive_vision.joint_history import JointHistory
from olive_vision.red_ball import angle_offsets, find_red_ball, tracking_goals

DEFAULT_IMAGE_TOPIC = '/olive/camera/eye/image/compressed'  # the course's camera, also olive_sim's
SERVOS = ('pan', 'tilt')
LOST_AFTER = 1.0      # s without the ball before search starts (search:=true)
SEARCH_PERIOD = 0.05  # s between two search goals
SEARCH_STEP = 0.02    # rad of the sweep's phase per search goal: one sweep in about 16 s
SEARCH_AMPLITUDE = 1.2  # rad: the pan servo sweeps this far to each side
SAY_EVERY = 1.0       # s between two lines about where the ball is
WAITING_EVERY = 5.0   # s between two "waiting for" lines


def gain_descriptor(description: str) -> ParameterDescriptor:
    return ParameterDescriptor(description=description, floating_point_range=[
        FloatingPointRange(from_value=0.0, to_value=1.0)])


class TrackObject(Node):

    def __init__(self) -> None:
        super().__init__('track_object')
        self.declare_parameter('image_topic', DEFAULT_IMAGE_TOPIC, ParameterDescriptor(
            description='sensor_msgs/msg/CompressedImage topic of the camera.', read_only=True))
        self.declare_parameter('horizontal_fov', 48.66, ParameterDescriptor(
            description="The camera's horizontal field of view, deg (the Olive camera's calibration).",
            floating_point_range=[FloatingPointRange(from_value=5.0, to_value=170.0)]))
        self.declare_parameter('gain_pan', 1.0, gain_descriptor(
            "Share of the ball's angle off the middle that each image turns the pan servo, 0..1."))
        self.declare_parameter('gain_tilt', 1.0, gain_descriptor(
            "Share of the ball's angle off the middle that each image turns the tilt servo, 0..1."))
        self.declare_parameter('min_area', 40.0, ParameterDescriptor(
            description='Smallest red blob taken for the ball, px.',
            floating_point_range=[FloatingPointRange(from_value=1.0, to_value=1e6)]))
        self.declare_parameter('search', False, ParameterDescriptor(
            description=f'Sweep the pan servo to find the ball when it has been lost for {LOST_AFTER} s.'))
        self.bounds = BoundParameters(self, SERVOS)  # pan_min .. tilt_max, each pair checked
        self.image_topic = self.get_parameter('image_topic').value
        self.torque = ServoTorque(self, SERVOS)
        # where each servo was lately, from its joint states: a picture steers from where the head was
        self.positions = {servo: JointHistory() for servo in SERVOS}
        self.publishers_ = {servo: self.create_publisher(Float32, f'/olive/servo/{servo}/goal/position', 10)
                            for servo in SERVOS}
        for servo in SERVOS:
            self.create_subscription(
                JointState, f'/olive/servo/{servo}/joint', self.joint_callback_of(servo), 10)
        # Best effort and volatile as the camera publishes (section 4.5); depth 1: only the newest
        # image matters, an older one shows the ball where it was.
        qos_profile = QoSProfile(
            depth=1,
            durability=QoSDurabilityPolicy.VOLATILE,
            reliability=QoSReliabilityPolicy.BEST_EFFORT)
        self.bridge = CvBridge()
        try:
            self.subscription = self.create_subscription(
                CompressedImage, self.image_topic, self.image_callback, qos_profile)
        except InvalidTopicNameException:
            raise ValueError(f"image_topic '{self.image_topic}' is not a valid topic name") from None
        self.last_seen = time.monotonic()
        self.tracking = False
        self.sweep = SineGoal(SEARCH_STEP)
        # Created once the torque is on: the servos ignore goals before.
        self.search_timer: Timer | None = None

    def enable_torque(self) -> None:
        self.torque.enable()
        self.search_timer = self.create_timer(SEARCH_PERIOD, self.search)

    def disable_torque(self) -> None:
        if self.search_timer is not None:
            self.search_timer.cancel()  # no goal may follow the torque requests
        self.destroy_subscription(self.subscription)  # no image may lead to a goal now
        self.torque.disable()

    def joint_callback_of(self, servo: str) -> Callable[[JointState], None]:
        def joint_callback(msg: JointState) -> None:
            if msg.position and math.isfinite(msg.position[0]):
                self.positions[servo].add(Time.from_msg(msg.header.stamp).nanoseconds, msg.position[0])
        return joint_callback

    def image_callback(self, msg: CompressedImage) -> None:
        if self.search_timer is None:
            return  # the torque is not on yet: the servos would ignore the goals
        try:
            image = self.bridge.compressed_imgmsg_to_cv2(msg)
        except CvBridgeError as error:
            self.get_logger().warning(f'image skipped: {error}', throttle_duration_sec=SAY_EVERY)
            return
        ball = find_red_ball(image, self.get_parameter('min_area').value)
        if ball is None:
            if self.tracking:
                self.tracking = False
                self.get_logger().warning('lost the red ball: the head holds still')
            return
        self.last_seen = time.monotonic()
        taken = Time.from_msg(msg.header.stamp).nanoseconds
        pan_then, tilt_then = self.positions['pan'].at(taken), self.positions['tilt'].at(taken)
        if pan_then is None or tilt_then is None:
            self.get_logger().info('waiting for the joint states of the pan and tilt servos',
                                   throttle_duration_sec=WAITING_EVERY)
            return
        height, width = image.shape[:2]
        x, y, _area = ball
        if not self.tracking:
            self.tracking = True
            self.get_logger().info(f'red ball at ({x:.0f}, {y:.0f}) px: tracking it')
        right, down = angle_offsets(x, y, width, height,
                                    math.radians(self.get_parameter('horizontal_fov').value))
        gain_pan, gain_tilt = self.get_parameter('gain_pan').value, self.get_parameter('gain_tilt').value
        pan, tilt = tracking_goals(pan_then, tilt_then, right, down, gain_pan, gain_tilt)
        self.publish_goals(pan, tilt)
        self.get_logger().info(
            f'ball {100 * (x - (width - 1) / 2) / width:+.1f} % of the width right, '
            f'{100 * (y - (height - 1) / 2) / height:+.1f} % of the height down of the middle',
            throttle_duration_sec=SAY_EVERY)

    def search(self) -> None:
        if not self.get_parameter('search').value or time.monotonic() - self.last_seen < LOST_AFTER:
            return
        self.get_logger().info('searching for the red ball', throttle_duration_sec=WAITING_EVERY)
        self.publish_goals(self.sweep.next(SEARCH_AMPLITUDE), 0.0)

    def publish_goals(self, pan: float, tilt: float) -> None:
        for servo, goal in (('pan', pan), ('tilt', tilt)):
            msg = Float32()
            msg.data = clamp(goal, *self.bounds.bounds(servo))
            self.publishers_[servo].publish(msg)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    track_object = None
    try:
        track_object = TrackObject()
        track_object.enable_torque()
        rclpy.spin(track_object)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except TorqueError as error:
        assert track_object is not None  # only enable_torque() raises it
        track_object.get_logger().error(str(error))
        sys.exit(1)
    except (ParameterException, ValueError) as error:
        if track_object is not None:
            raise
        print(f'track_object: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if track_object is not None:
            track_object.disable_torque()
            track_object.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
