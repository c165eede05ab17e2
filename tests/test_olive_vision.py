"""olive_vision over real DDS against the simulated kit: the head tracks the red ball, answers gestures.

The numbers of section 4.6's tracker come from the camera's own images: where the ball is in each
one, against the time the tracker started tracking (both on the ROS clock).
"""

import math
import time

import cv2
import numpy as np
import pytest
from olive_kit.description import BALL_COLOUR
from owl_common.images import find_colour
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros_harness import wait_for_messages, wait_until
from sensor_msgs.msg import CompressedImage
from servo_helpers import assert_clean_servo, collect, start_servo
from std_msgs.msg import String
from turtlesim.msg import Pose
from web_harness import keep_screenshot

IMAGE_TOPIC = '/olive/camera/eye/image/compressed'
GESTURE_TOPIC = '/olive/camera/eye/tpu/gesture'
CAMERA = '/olive_camera_eye_dcm_srv'
CAMERA_QOS = QoSProfile(depth=100, durability=DurabilityPolicy.VOLATILE,
                        reliability=ReliabilityPolicy.BEST_EFFORT)
WIDTH = 640


def rgb_of(msg: CompressedImage) -> np.ndarray:
    bgr = cv2.imdecode(np.frombuffer(bytes(msg.data), np.uint8), cv2.IMREAD_COLOR)
    assert bgr is not None, 'not a JPEG'
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def png(msg: CompressedImage) -> bytes:
    """A JPEG image message as PNG bytes, for the documentation's screenshots."""
    return cv2.imencode('.png', cv2.cvtColor(rgb_of(msg), cv2.COLOR_RGB2BGR))[1].tobytes()


def ball_error(msg: CompressedImage) -> float | None:
    """How far the ball is from the image's middle, as a share of the width; None if not in sight."""
    rgb = rgb_of(msg)
    ball = find_colour(rgb, BALL_COLOUR)
    if ball is None:
        return None
    height, width = rgb.shape[:2]
    return math.hypot(ball[0] - (width - 1) / 2, ball[1] - (height - 1) / 2) / width


def stamp(msg: CompressedImage) -> float:
    return msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9


def start_tracking(ros, **ball):
    """The servos, the camera's images, track_object and when it began tracking; all started together.

    The tracker tracks only once the servos' torque is on and the camera's images come; the probe
    subscribes before any of them starts, so it has the images from before then on.
    """
    images = ros.probe.collect(CompressedImage, IMAGE_TOPIC, CAMERA_QOS)
    servos = {name: start_servo(ros, name) for name in ('pan', 'tilt')}
    args = [arg for key, value in {'scene': 'ball', **ball}.items() for arg in ('-p', f'{key}:={value}')]
    ros.run('olive_sim', 'camera_sim', '--ros-args', *args)
    tracker = ros.run('olive_vision', 'track_object')
    wait_for_messages(images, 3, timeout=60)
    [line] = tracker.wait_for(r'\[(\d+\.\d+)\] \[track_object\]: red ball at .* tracking it$', timeout=60)
    return servos, images, tracker, float(line.group(1))


# Two servos, the camera at 30 images a second and the tracker: starved beside two other tests, the
# camera sent 11 images in 4 s and the tracker, fed late images, swung across the ball.
@pytest.mark.whole_kit
def test_the_tracker_centres_a_still_ball_from_a_0_4_rad_offset_within_2_s(ros):
    servos, images, tracker, started = start_tracking(ros, ball_speed=0.0, ball_azimuth=0.4,
                                                      ball_elevation=-0.1)
    wait_until(lambda: images and stamp(images[-1]) > started + 4.0, 30, '4 s of images')
    errors = [(stamp(m) - started, ball_error(m)) for m in list(images) if stamp(m) >= started]
    first = errors[0][1]
    assert first is not None, errors[:3]
    assert first > 0.25, errors[:3]  # the ball starts well off the middle
    # Centred: from the first image after the last one off the middle (a settling time). A swing
    # through the middle on the way is not centred: on a busy machine the tilt still settled after it.
    last_off = max(index for index, (_, e) in enumerate(errors) if e is None or e >= 0.02)
    assert last_off + 1 < len(errors), f'the ball was still off the middle in the last image: {errors[-5:]}'
    settled = errors[last_off + 1][0]
    print(f'still ball from 0.4 rad: centred (< 2 % of the width) {settled:.2f} s after tracking began, '
          'and stayed')
    assert settled < 2.0, [(round(t, 2), e) for t, e in errors if t > 1.5 and (e is None or e >= 0.02)]
    keep_screenshot('camera_ball_tracked', png(images[-1]))
    tracker.stop_cleanly(timeout=15)
    for servo in servos.values():
        assert_clean_servo(servo)


# The moving ball's path: it starts still, right of the middle, and once the tracker holds it, goes left
# at 0.2 rad/s; judged from 2 to 8 s after it set off (azimuth 0.05 to 1.25 rad), always within the pan
# servo's reach (+-1.57 rad). From the camera's default start the ball was beyond that reach 8 s after
# the tracker first saw it: the test passed only when a slow start had let the ball go round once.
BALL_SETS_OFF_AT = -0.35  # rad of azimuth: in sight of the camera at rest (half its view: 0.42 rad)
JUDGED_FROM, JUDGED_UNTIL = 2.0, 8.0  # s after the ball set off


@pytest.mark.whole_kit
def test_the_tracker_follows_a_moving_ball_within_5_percent_of_the_width(ros):
    servos, images, tracker, _ = start_tracking(ros, ball_speed=0.0, ball_azimuth=BALL_SETS_OFF_AT)
    tracker.wait_for(r'ball [-+]\d\.\d % of the width right', timeout=10)  # within 10 % of the middle
    [result] = ros.probe.set_parameters(CAMERA, ball_speed=0.2)
    assert result.successful, result.reason
    set_off = time.time()
    until = set_off + JUDGED_UNTIL
    wait_until(lambda: images and stamp(images[-1]) > until, 30, f'{JUDGED_UNTIL} s of images')
    errors = [ball_error(m) for m in list(images) if set_off + JUDGED_FROM < stamp(m) <= until]
    locked = [error for error in errors if error is not None]
    assert len(locked) == len(errors), 'the ball left the picture'
    mean = sum(locked) / len(locked)
    print(f'moving ball (0.2 rad/s): mean error {100 * mean:.2f} % of the width, '
          f'largest {100 * max(locked):.2f} %, over {len(locked)} images')
    assert mean < 0.05
    tracker.stop_cleanly(timeout=15)
    for servo in servos.values():
        assert_clean_servo(servo)


def start_person(ros, gesture='both_hands_down'):
    """camera_sim with a person making a gesture; the gestures its app says, once it has said the first."""
    ros.run('olive_sim', 'camera_sim', '--ros-args', '-p', 'scene:=person', '-p', f'gesture:={gesture}')
    gestures = ros.probe.collect(String, GESTURE_TOPIC)
    wait_until(lambda: gestures and gestures[-1].data != 'none', 60, 'a recognised gesture')
    return gestures


def set_gesture(ros, gesture):
    assert all(r.successful for r in ros.probe.set_parameters(CAMERA, gesture=gesture))


def test_the_gesture_app_says_the_gesture_and_draws_the_skeleton_and_the_head_nods(ros):
    servos = {name: start_servo(ros, name) for name in ('pan', 'tilt')}
    # Started with the kit: it waits for the servos' torque, then for the camera's gestures.
    control = ros.run('olive_vision', 'gesture_control')
    gestures = start_person(ros)
    assert gestures[-1].data == '1'  # both hands down
    [refused] = ros.probe.set_parameters(CAMERA, gesture='waving')
    assert not refused.successful
    assert "unknown gesture 'waving': expected one of both_hands_down" in refused.reason
    skeletons = ros.probe.collect(CompressedImage, '/olive/camera/eye/tpu/compressed')
    wait_for_messages(skeletons, 1, timeout=20)
    rgb = rgb_of(skeletons[-1])
    yellow = (np.abs(rgb.astype(int) - (255, 255, 0)).max(axis=2) < 60).sum()
    assert yellow > 500, f'{yellow} yellow px: no skeleton drawn'
    keep_screenshot('camera_gesture_skeleton', png(skeletons[-1]))
    control.wait_for(r'\[gesture_control\]: gesture 1 \(both hands down\): rest$', timeout=60)
    tilt_goals = collect(ros, 'tilt', 'goal/position')
    set_gesture(ros, 'both_hands_up')
    wait_until(lambda: gestures[-1].data == '2', 10, 'gesture 2 said')
    control.wait_for(r'\[gesture_control\]: gesture 2 \(both hands up\): nod$', timeout=10)
    wait_until(lambda: any(g.data == pytest.approx(0.3) for g in tilt_goals), 10, 'the nod going down')
    wait_until(lambda: tilt_goals and tilt_goals[-1].data == 0.0 and any(
        g.data == pytest.approx(-0.1) for g in tilt_goals), 10, 'the nod up and back to the middle')
    control.stop_cleanly(timeout=15)
    for servo in servos.values():
        assert_clean_servo(servo)


def test_with_target_turtle_the_gestures_drive_turtlesims_turtle(ros):
    poses = ros.probe.collect(Pose, '/turtle1/pose')
    ros.run('turtlesim', 'turtlesim_node', '--headless')
    control = ros.run('olive_vision', 'gesture_control', '--ros-args', '-p', 'target:=turtle')
    start_person(ros, 'both_hands_up')
    wait_for_messages(poses, 1, timeout=30)
    control.wait_for(r'gesture 2 \(both hands up\): turtle \(1.5, 0.0\)$', timeout=60)
    x = poses[-1].x
    wait_until(lambda: poses[-1].x > x + 1.0, 10, 'the turtle driving forward')
    set_gesture(ros, 'hands_on_hip')
    control.wait_for(r'gesture 7 \(hands on hip\): turtle \(0.0, 0.0\)$', timeout=10)
    wait_until(lambda: poses[-1].linear_velocity == 0.0, 10, 'the turtle stopped')
    control.stop_cleanly(timeout=15)


def test_bad_scenes_gestures_speeds_and_places_get_one_line_each_and_nothing_breaks(ros):
    # Every bad start is on its own: they all start at once, and each is judged once it has ended.
    bad = ros.run('olive_sim', 'camera_sim', '--ros-args', '-p', 'scene:=beach')
    nodes = [(executable, message, ros.run('olive_vision', executable, '--ros-args', *args))
             for executable, args, message in (
                 ('track_object', ['-p', 'gain_pan:=1.5'], 'out of range'),
                 ('track_object', ['-p', 'image_topic:=my camera'], "image_topic 'my camera' is not a valid"),
                 ('gesture_control', ['-p', 'target:=fish'], "target 'fish' is not one of head, turtle"))]
    launches = [(message, ros.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py', 'web_port:=0',
                                       argument]))
                for argument, message in (
                    ('scene:=beach', "scene must be one of landmarks, ball, person, got 'beach'"),
                    ('ball_speed:=-1',
                     "ball_speed must be a number of rad/s from 0 (still) to 2.0, got '-1'"),
                    ('ball_swing:=4',
                     "ball_swing must be a number of rad from 0 (round the robot) to 3.1416, got '4'"),
                    ('gesture:=waving', 'gesture must be one of both_hands_down'))]
    assert bad.wait(60) == 2
    assert "error: unknown scene 'beach': expected one of landmarks, ball, person" in bad.output
    assert 'Traceback' not in bad.output
    # Once the bad camera has gone: both are /olive_camera_eye_dcm_srv, whose parameters are set below.
    # A still ball: a moving one leaves the picture after about 2 s, and this test takes longer.
    ros.run('olive_sim', 'camera_sim', '--ros-args', '-p', 'scene:=ball', '-p', 'ball_speed:=0.0')
    images = ros.probe.collect(CompressedImage, IMAGE_TOPIC, CAMERA_QOS)
    wait_for_messages(images, 3, timeout=60)
    for values, reason in (({'ball_speed': -0.2}, 'out of range'), ({'ball_elevation': 1.2}, 'out of range'),
                           ({'ball_swing': -1.0}, 'out of range'),
                           ({'ball_azimuth': math.nan}, 'out of range'),
                           ({'gesture': 'both_hands_up'},
                            "there is no person in the scene 'ball' (start the camera with scene:=person)"),
                           ({'scene': 'person'}, 'read-only')):
        [result] = ros.probe.set_parameters(CAMERA, **values)
        assert not result.successful, values
        assert reason in result.reason, (values, result.reason)
    count = len(images)
    wait_for_messages(images, count + 10, timeout=20)  # the camera goes on
    assert ball_error(images[-1]) is not None
    for executable, message, node in nodes:
        assert node.wait(30) == 2
        assert len(node.lines) == 1, node.output
        assert node.lines[0].startswith(f'{executable}: error: '), node.output
        assert message in node.output
    for message, launch in launches:
        launch.wait(timeout=60)
        assert message in launch.output
        assert 'Traceback' not in launch.output
        assert 'process started' not in launch.output
