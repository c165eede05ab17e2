"""camera_sim: a simulated Olive camera (OLV-CAM01) on the Owl Kit's pan/tilt head."""

from __future__ import annotations

import json
import math
import time

from olive_kit.description import joint_topic
from owl_common import quaternion as quat
from owl_common.quaternion import Quaternion
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, SetParametersResult
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, QoSProfile
from rclpy.serialization import deserialize_message, serialize_message
from sensor_msgs.msg import CameraInfo, CompressedImage, JointState
from std_msgs.msg import Header, String

from olive_sim.camera_render import LANDMARKS, NO_RED_LANDMARKS, CameraRenderer
from olive_sim.imu_output import ImuOutput, reliability
from olive_sim.module_node import OliveModule, describe, run_module
from olive_sim.scene_draw import SceneView
from olive_sim.scene_model import (
    BALL_ELEVATION_RANGE,
    BALL_MAX_SPEED,
    BALL_MAX_SWING,
    BALL_START,
    GESTURE_NAMES,
    NO_GESTURE,
    SCENES,
    BallPath,
    gesture_named,
    person_directions,
    wrap,
)
from olive_sim.serialized import STAMP_MARKER, SerializedTemplate, joint_state_position

# Horizontal field of view of the vendor's shipped calibration (K of calibration/ost.yaml).
DEFAULT_FOV_DEG = 48.66
# The gesture app of the real camera (a vendor example) classifies every frame it can keep up with;
# the simulated one answers for every TPU_EVERY-th frame (10 Hz at the default 30 fps).
TPU_EVERY = 3
SCENE_RATE = 10.0  # Hz of the scene topic (where the ball and the person are)


class CameraModule(OliveModule):
    """The camera_sim node: JPEG images of the scene where the pan/tilt head points it, and its IMU."""

    def __init__(self, namespace: str) -> None:
        super().__init__('camera', namespace, serial='1715257918934')
        self.declare_parameter('width', 640, describe('Image width [px].', True, integer_range=[
            IntegerRange(from_value=16, to_value=4096, step=1)]))
        self.declare_parameter('height', 480, describe('Image height [px].', True, integer_range=[
            IntegerRange(from_value=16, to_value=4096, step=1)]))
        self.declare_parameter('fps', 30.0, describe('Frame rate [Hz].', True, floating_point_range=[
            FloatingPointRange(from_value=0.1, to_value=240.0)]))
        self.declare_parameter('jpeg_quality', 80, describe('JPEG quality 1..100.', integer_range=[
            IntegerRange(from_value=1, to_value=100, step=1)]))
        self.declare_parameter('horizontal_fov', DEFAULT_FOV_DEG, describe(
            'Horizontal field of view [deg].', True, floating_point_range=[
                FloatingPointRange(from_value=5.0, to_value=160.0)]))
        self.declare_parameter('image_reliability', 'best_effort', describe(
            'Reliability of image/compressed and image/camera_info: best_effort (as the course shows) '
            'or reliable.', True))
        self.declare_parameter('frame_id', 'olive', describe('header.frame_id of the images.', True))
        self.declare_parameter('pan_joint_topic', joint_topic('pan'), describe(
            'JointState topic of the pan servo the camera sits on.', True))
        self.declare_parameter('tilt_joint_topic', joint_topic('tilt'), describe(
            'JointState topic of the tilt servo the camera sits on.', True))
        self._declare_scene_parameters()
        value = self.get_parameter
        self.scene = value('scene').value
        if self.scene not in SCENES:
            raise ValueError(f"unknown scene '{self.scene}': expected one of {', '.join(SCENES)}")
        self.ball = BallPath(value('ball_azimuth').value, value('ball_elevation').value,
                             value('ball_speed').value, time.monotonic(), value('ball_swing').value)
        self.gesture = gesture_named(value('gesture').value)
        self.recognised = NO_GESTURE  # what the gesture app says: its last recognised gesture
        self.renderer = CameraRenderer(
            value('width').value, value('height').value, math.radians(value('horizontal_fov').value),
            landmarks=LANDMARKS if self.scene == 'landmarks' else NO_RED_LANDMARKS)
        self.frame_id = value('frame_id').value
        self.pan = 0.0
        self.tilt = 0.0
        self.frames = 0
        self.jpeg_quality = value('jpeg_quality').value
        qos = QoSProfile(depth=10, durability=DurabilityPolicy.VOLATILE,
                         reliability=reliability(value('image_reliability').value, 'image_reliability'))
        self.image_publisher = self.create_publisher(CompressedImage, self.topic('image/compressed'), qos)
        self.info_publisher = self.create_publisher(CameraInfo, self.topic('image/camera_info'), qos)
        # Only its stamp changes: published as serialized bytes with the stamp patched in.
        self.camera_info = SerializedTemplate(serialize_message(self._camera_info()), [])
        # Polled by the frame and IMU threads just before they use pan and tilt, as bytes: only
        # the position is read from them.
        # Each joint's callback runs under its subscription's lock, the frames on their own thread.
        self.pan_traffic, self.tilt_traffic, self.frame_traffic = (self.traffic.counter() for _ in range(3))
        self.joints = [self.create_polled_subscription(JointState, value(topic).value, callback, 10,
                                                       raw=True)
                       for topic, callback in (('pan_joint_topic', self._on_pan),
                                               ('tilt_joint_topic', self._on_tilt))]
        if self.scene != 'landmarks':
            # Not a real module's: where the ball and the person are, for the robot view and tests
            # (as imu_sim's true_orientation), at SCENE_RATE Hz; the newest one kept for a late joiner.
            self.scene_publisher = self.create_publisher(
                String, f'/{self.get_name()}/scene',
                QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
            self.create_timer(1.0 / SCENE_RATE, self._publish_scene)
        if self.scene == 'person':  # the camera runs its gesture app (a vendor example)
            tpu = QoSProfile(depth=1)
            self.tpu_publisher = self.create_publisher(CompressedImage, self.topic('tpu/compressed'), tpu)
            self.gesture_publisher = self.create_publisher(String, self.topic('tpu/gesture'), tpu)
        self.add_on_set_parameters_callback(self._check_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)
        self.output = ImuOutput(self, self.topic, f'{namespace}_body_link', self.orientation)
        self.frame_thread = self.create_periodic(value('fps').value, self.publish_frame, 'frames')

    def _declare_scene_parameters(self) -> None:
        self.declare_parameter('scene', 'landmarks', describe(
            f"What stands around the robot: {', '.join(SCENES)} (the landmarks, and a red ball to track, "
            'or a person making gestures).', True))
        self.declare_parameter('ball_speed', 0.1, describe(
            "Speed of the ball along its path around the robot [rad/s of azimuth]; 0 keeps it still.",
            floating_point_range=[FloatingPointRange(from_value=0.0, to_value=BALL_MAX_SPEED)]))
        self.declare_parameter('ball_swing', 0.0, describe(
            'How far the ball swings to either side of where it was put [rad of azimuth], to and fro in '
            'front of the robot at ball_speed; 0 sends it round the robot instead.',
            floating_point_range=[FloatingPointRange(from_value=0.0, to_value=BALL_MAX_SWING)]))
        self.declare_parameter('ball_azimuth', BALL_START[0], describe(
            'Where the ball is put: its azimuth [rad], 0 straight ahead, positive to the left; it moves '
            'on from there.',
            floating_point_range=[FloatingPointRange(from_value=-math.pi, to_value=math.pi)]))
        low, high = BALL_ELEVATION_RANGE
        self.declare_parameter('ball_elevation', BALL_START[1], describe(
            'Where the ball is put: its elevation [rad] above the horizon; it moves on from there.',
            floating_point_range=[FloatingPointRange(from_value=low, to_value=high)]))
        self.declare_parameter('gesture', GESTURE_NAMES[0], describe(
            f"The person's gesture in the person scene: {', '.join(GESTURE_NAMES)}."))

    def _check_parameters(self, parameters: list[Parameter]) -> SetParametersResult:
        for p in parameters:
            needs = 'ball' if p.name.startswith('ball_') else 'person' if p.name == 'gesture' else None
            if needs is not None and self.scene != needs:
                return SetParametersResult(successful=False, reason=(
                    f"there is no {needs} in the scene '{self.scene}' "
                    f'(start the camera with scene:={needs})'))
            if p.name == 'gesture' and p.value not in GESTURE_NAMES:
                return SetParametersResult(successful=False, reason=(
                    f"unknown gesture '{p.value}': expected one of {', '.join(GESTURE_NAMES)}"))
            if p.name.startswith('ball_') and not math.isfinite(p.value):
                return SetParametersResult(successful=False, reason=f'{p.name} must be a finite number')
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters: list[Parameter]) -> None:
        now = time.monotonic()
        for p in parameters:
            if p.name == 'jpeg_quality':
                self.jpeg_quality = p.value
            elif p.name == 'gesture':
                self.gesture = gesture_named(p.value)
            elif p.name == 'ball_speed':
                self.ball = self.ball.moved(now, speed=p.value)
            elif p.name == 'ball_swing':
                self.ball = self.ball.moved(now, swing=p.value)
            elif p.name == 'ball_azimuth':
                self.ball = self.ball.moved(now, azimuth=wrap(p.value))
            elif p.name == 'ball_elevation':
                self.ball = self.ball.moved(now, elevation=p.value)

    def _publish_scene(self) -> None:
        view = self.scene_view(time.monotonic())
        if view is None:
            return
        state: dict[str, object] = {'scene': self.scene}
        if view.ball is not None:
            state['ball'] = list(view.ball)
        if view.person is not None:
            state.update(gesture=self.gesture.name, keypoints={k: list(v) for k, v in view.person.items()})
        self.scene_publisher.publish(String(data=json.dumps(state)))

    def scene_view(self, t: float) -> SceneView | None:
        """What stands in front of the panorama at time t (time.monotonic()); None in the landmarks scene."""
        if self.scene == 'ball':
            return SceneView(ball=self.ball.at(t))
        if self.scene == 'person':
            return SceneView(person=person_directions(self.gesture))
        return None

    def _poll_joints(self) -> None:
        for joint in self.joints:
            joint.poll()

    def orientation(self, t: float) -> Quaternion:
        """The camera's true orientation: yaw by pan, pitched down by tilt."""
        self._poll_joints()
        return quat.from_euler(0.0, self.tilt, self.pan)

    def _joint_position(self, data: bytes, which: str) -> float | None:
        try:
            position = joint_state_position(data)
        except ValueError:  # an encoding we do not read directly
            msg = deserialize_message(data, JointState)
            position = msg.position[0] if msg.position else None
        if position is None or not math.isfinite(position):
            self.warn(f'{which} joint', f'{which} joint state without a finite position ignored')
            return None
        return position

    def _on_pan(self, data: bytes) -> None:
        self.pan_traffic.received += len(data)
        position = self._joint_position(data, 'pan')
        if position is not None:
            self.pan = position

    def _on_tilt(self, data: bytes) -> None:
        self.tilt_traffic.received += len(data)
        position = self._joint_position(data, 'tilt')
        if position is not None:
            self.tilt = position

    def _camera_info(self) -> CameraInfo:
        r = self.renderer
        info = CameraInfo(width=r.width, height=r.height, distortion_model='plumb_bob')
        info.d = [0.0, 0.0, 0.0, 0.0, 0.0]
        info.k = [r.fx, 0.0, r.cx, 0.0, r.fy, r.cy, 0.0, 0.0, 1.0]
        info.r = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        info.p = [r.fx, 0.0, r.cx, 0.0, 0.0, r.fy, r.cy, 0.0, 0.0, 0.0, 1.0, 0.0]
        info.header.frame_id = self.frame_id
        info.header.stamp.sec, info.header.stamp.nanosec = STAMP_MARKER
        return info

    def nobody_watches(self) -> bool:
        """No subscription matches the images nor the gesture app's topics: a frame would reach nobody."""
        publishers = [self.image_publisher]
        if self.scene == 'person':
            publishers += [self.tpu_publisher, self.gesture_publisher]
        return all(publisher.get_subscription_count() == 0 for publisher in publishers)

    def publish_frame(self) -> None:
        """Render, encode and publish one frame and its camera info (the frame thread calls it at fps).

        A frame nobody subscribes to is counted but not rendered: rendering and encoding are most of
        the camera's CPU (11.7 % of a core of the idle kit's 27.5 %), and a class server runs a kit
        per student. Its camera info still goes out.
        """
        self.frames += 1
        now = self.now_ns()
        if self.nobody_watches():
            self.info_publisher.publish(self.camera_info.fill(now, ()))
            return
        self._poll_joints()
        seconds = now / 1e9
        clock = time.strftime('%H:%M:%S', time.gmtime(seconds))
        caption = f'#{self.frames}  {clock}.{int(seconds % 1 * 1000):03d}'
        msg = CompressedImage(format='jpeg')
        msg.header.stamp.sec, msg.header.stamp.nanosec = divmod(now, 1_000_000_000)
        msg.header.frame_id = self.frame_id
        msg.data = self.renderer.jpeg(self.pan, self.tilt, caption, self.jpeg_quality,
                                      self.scene_view(time.monotonic()))
        self.image_publisher.publish(msg)
        info = self.camera_info.fill(now, ())
        self.info_publisher.publish(info)
        self.frame_traffic.sent += len(msg.data) + len(info) + 64  # 64: the image's header and format
        if self.scene == 'person' and self.frames % TPU_EVERY == 0:
            self._run_gesture_app(msg.header)

    def _run_gesture_app(self, header: Header) -> None:
        """What the camera's gesture app publishes for the frame just made: skeleton image and gesture.

        As the app, it classifies a gesture only when it sees all 17 keypoints, and keeps saying the
        last one it recognised (none before the first).
        """
        placed = self.renderer.placed
        r = self.renderer
        visible = {} if placed is None else {
            name: point for name, point in placed.keypoints.items()
            if 0 <= point[0] < r.width and 0 <= point[1] < r.height}
        if placed is not None and placed.inside(r.width, r.height):
            self.recognised = self.gesture.label
        annotated = CompressedImage(header=header, format='jpeg')
        annotated.data = r.annotated_jpeg(visible, self.jpeg_quality)
        self.tpu_publisher.publish(annotated)
        self.gesture_publisher.publish(String(data=self.recognised))

    def imu_orientation(self) -> Quaternion | None:
        """The orientation the camera's IMU last published (None before its first reading)."""
        return self.output.latest

    def temperature(self) -> float:
        """The camera board's temperature in deg C, a constant 42."""
        return 42.0


def main(args: list[str] | None = None) -> None:
    """camera_sim's entry point: one camera module, in namespace `eye` by default."""
    run_module(CameraModule, 'eye', args)


if __name__ == '__main__':
    main()
