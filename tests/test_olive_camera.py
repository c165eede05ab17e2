"""olive_camera over real DDS against olive_sim's camera, with and without a display.

display_camera without a display (one line, the camera's images in its window's seam) and with one
(a real window under Xvfb), the launch file with the kit, the QoS the course chose and why, bad
input, Ctrl-C.
"""

import signal
import time

import cv2
import numpy as np
import pytest
from desktop import NO_DISPLAY, REAL_WINDOWS
from olive_sim.camera_render import LANDMARKS
from owl_common.images import find_colour
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros_harness import endpoints, wait_for_messages, wait_until
from sensor_msgs.msg import CompressedImage
from std_msgs.msg import Float32

IMAGE_TOPIC = '/olive/camera/eye/image/compressed'
NOTICE_START = ("display_camera: no display (DISPLAY is not set), so the window 'camera' is not shown; the "
                'program runs on without it. ')
# OWL_WINDOWS_DIR set but empty: no windows' folder, so the line points at rqt instead of `owl windows`.
NOTICE = NOTICE_START + 'To see the camera, run rqt and open Plugins > Visualization > Image View'

COURSE_QOS = QoSProfile(depth=10, durability=DurabilityPolicy.VOLATILE,
                        reliability=ReliabilityPolicy.BEST_EFFORT)
RED = LANDMARKS[0][1]  # RGB of the tower straight ahead


def decode(data):
    """RGB pixels of JPEG bytes."""
    bgr = cv2.imdecode(np.frombuffer(bytes(data), np.uint8), cv2.IMREAD_COLOR)
    assert bgr is not None, 'not a JPEG'
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB)


def jpeg(image_bgr):
    return cv2.imencode('.jpg', image_bgr)[1].tobytes()


def seam_image(path):
    """RGB pixels of the window's file in the seam, or None while there is none."""
    return decode(path.read_bytes()) if path.exists() else None


def file_version(path):
    """What changes when a file is replaced (the seam replaces a window's file with each image it writes)."""
    status = path.stat()
    return status.st_ino, status.st_mtime_ns


def own_lines(process, node='display_camera'):
    """The lines a process printed itself: not rclpy's log lines of the node."""
    return [line for line in process.lines if f'] [{node}]: ' not in line]


def test_without_a_display_it_says_so_once_and_its_window_gets_the_cameras_images(ros, tmp_path):
    ros.run('olive_sim', 'camera_sim')
    display_camera = ros.run('olive_camera', 'display_camera',
                             env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    display_camera.wait_for(r"\[display_camera\]: images on /olive/camera/eye/image/compressed \(640x480 "
                            r"colour\): showing them in the window 'camera'$", timeout=60)
    window = tmp_path / f'display_camera-{display_camera.pid}' / 'cv2-camera.jpg'
    wait_until(window.exists, 20, "the window's image in the seam")
    images = ros.probe.collect(CompressedImage, IMAGE_TOPIC, COURSE_QOS)
    wait_for_messages(images, 5, timeout=20)
    shown = seam_image(window)
    assert shown.shape == (480, 640, 3)
    # What the window shows is the camera's picture: the red tower straight ahead, where the
    # camera's own images have it, and the same pixels give or take JPEG.
    tower = find_colour(shown, RED)
    assert tower is not None
    assert tower == pytest.approx(find_colour(decode(images[-1].data), RED), abs=3)
    assert min(np.abs(shown.astype(int) - decode(m.data).astype(int)).mean() for m in images[-5:]) < 6
    # It runs on: the window's file is replaced by a later image.
    seen = file_version(window)
    wait_until(lambda: file_version(window) != seen, 10, "a later image in the window's file")
    assert display_camera.running()
    display_camera.stop_cleanly(timeout=10)
    assert own_lines(display_camera) == [f"{NOTICE_START}To see it in a browser, run 'owl windows' "
                                         f'(its frames go to {window.parent})']
    assert 'Traceback' not in display_camera.output
    assert not window.parent.exists()


def test_without_a_display_and_without_the_seam_the_line_is_exactly_this(ros):
    images = ros.probe.collect(CompressedImage, IMAGE_TOPIC, COURSE_QOS)
    ros.run('olive_sim', 'camera_sim')
    display_camera = ros.run('olive_camera', 'display_camera', env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': ''})
    display_camera.wait_for(r'no display', timeout=60)
    # While 30 more images come, which display_camera shows too: a line that came with each would be there.
    wait_for_messages(images, len(images) + 30, timeout=30)
    display_camera.stop_cleanly(timeout=10)
    assert own_lines(display_camera) == [NOTICE]


def test_with_a_display_it_opens_a_real_window_named_camera(ros, x_display, tmp_path):
    ros.run('olive_sim', 'camera_sim')
    display_camera = ros.run('olive_camera', 'display_camera',
                             env={**x_display.env(), **REAL_WINDOWS, 'OWL_WINDOWS_DIR': str(tmp_path)})
    x_display.wait_for_window('^camera$', timeout=60)
    time.sleep(1.0)
    display_camera.stop_cleanly(timeout=10)
    assert own_lines(display_camera) == []  # no line about a display, nothing from Qt
    assert list(tmp_path.iterdir()) == []   # real windows: the seam is not used
    assert not x_display.windows('^camera$')       # Ctrl-C closed it


def test_it_says_which_topic_it_waits_for_and_skips_undecodable_images_with_a_warning(ros, tmp_path):
    display_camera = ros.run('olive_camera', 'display_camera', '--ros-args', '-p', 'image_topic:=/test/image',
                             env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    display_camera.wait_for(
        r'\[display_camera\]: waiting for images on /test/image \(0 publisher\(s\) so far\)$', timeout=60)
    probe = ros.probe
    publisher = probe.node.create_publisher(CompressedImage, '/test/image', COURSE_QOS)
    wait_until(lambda: publisher.get_subscription_count() > 0, 20, "display_camera's subscription")
    for _ in range(10):
        publisher.publish(CompressedImage(format='jpeg', data=b'not a jpeg'))
        time.sleep(0.05)
    display_camera.wait_for(r"\[display_camera\]: image skipped: cannot decode 10 bytes of compressed image "
                            r"\(format 'jpeg'\): not an image OpenCV reads$", timeout=10)
    image = np.zeros((48, 64, 3), np.uint8)
    image[:, :32] = (0, 0, 255)  # BGR red
    publisher.publish(CompressedImage(format='jpeg', data=jpeg(image)))
    display_camera.wait_for(r"images on /test/image \(64x48 colour\): showing them in the window 'camera'$")
    window = tmp_path / f'display_camera-{display_camera.pid}' / 'cv2-camera.jpg'
    wait_until(window.exists, 10, "the window's image in the seam")
    shown = seam_image(window)
    assert shown.shape == (48, 64, 3)
    assert np.abs(shown[24, 10].astype(int) - (255, 0, 0)).max() < 30
    assert display_camera.output.count('image skipped') == 1  # ten bad images in 0.5 s: one warning
    display_camera.wait_for(r'no image on /test/image for 2.0 s$', timeout=10)
    assert display_camera.running()
    display_camera.stop_cleanly(timeout=10)
    assert 'Traceback' not in display_camera.output


@pytest.mark.parametrize(('args', 'message'), [
    (['-p', 'image_topic:=5'],
     "Trying to set parameter 'image_topic' to '5' of type 'INTEGER', expecting type 'STRING'"),
    (['-p', 'image_topic:=my camera'], "image_topic 'my camera' is not a valid topic name"),
])
def test_bad_startup_parameters_end_with_one_line_and_code_2(ros, args, message):
    display_camera = ros.run('olive_camera', 'display_camera', '--ros-args', *args, env=NO_DISPLAY)
    assert display_camera.wait(30) == 2
    assert len(display_camera.lines) == 1, display_camera.output
    assert display_camera.lines[0].startswith('display_camera: error: ')
    assert message in display_camera.output


def test_the_courses_qos_receives_the_camera_and_a_reliable_subscription_receives_nothing(ros):
    ros.run('olive_sim', 'camera_sim', '--ros-args', '-p', 'fps:=10.0')
    display_camera = ros.run('olive_camera', 'display_camera', env=NO_DISPLAY)
    probe = ros.probe
    [subscription] = endpoints(probe, IMAGE_TOPIC, 'subscriptions')
    assert subscription.node_name == 'display_camera'
    assert subscription.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT
    assert subscription.qos_profile.durability == DurabilityPolicy.VOLATILE
    reliable = probe.collect(CompressedImage, IMAGE_TOPIC, 10)  # the default profile: reliable
    course = probe.collect(CompressedImage, IMAGE_TOPIC, COURSE_QOS)
    # The camera finds both subscriptions at once: had it matched the reliable one, that would have these too.
    wait_for_messages(course, 10, timeout=30)
    display_camera.wait_for(r'images on /olive/camera/eye/image/compressed', timeout=30)
    assert reliable == []  # a reliable subscription is never connected to the best-effort camera
    display_camera.stop_cleanly(timeout=10)


@pytest.mark.whole_kit
def test_the_launch_file_starts_imu_control_robot_and_display_camera_with_the_kit(ros):
    kit = ros.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py'], label='owl_kit.launch')
    launch = ros.command(['ros2', 'launch', 'olive_camera', 'robot_camera.launch.py'], env=NO_DISPLAY,
                         label='robot_camera.launch')
    launch.wait_for(r'\[imu_control_robot-1\].*torque enabled: pan, tilt', timeout=60)
    launch.wait_for(r"\[display_camera-2\].*images on /olive/camera/eye/image/compressed \(640x480 colour\)",
                    timeout=60)
    launch.wait_for(r'\[display_camera-2\] display_camera: no display \(DISPLAY is not set\)', timeout=10)
    goals = ros.probe.collect(Float32, '/olive/servo/pan/goal/position')
    wait_for_messages(goals, 20, timeout=20, what='pan goals from imu_control_robot')
    launch.send_signal(signal.SIGINT)
    assert launch.wait(30) == 0
    assert launch.output.count('process has finished cleanly') == 2, launch.output
    assert launch.output.count('no display') == 1
    assert 'Traceback' not in launch.output
    kit.stop_cleanly(timeout=20)
