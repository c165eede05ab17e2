"""Section 4.5: the camera's images, and the launch file of the whole robot."""

from __future__ import annotations

from pathlib import Path

from olive_kit.description import CAMERA_TOPIC, goal_topic

from owl_cli.check.catalogue import Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    Session,
    headless,
    launch_files,
)

SECTION = Section()


@SECTION.check(
    'display_camera',
    '4.5',
    'olive_camera',
    "shows the camera's CompressedImage frames with cv2.imshow, with a best-effort QoS",
)
def check_display_camera(s: Session) -> None:
    """Run display_camera headless: a best-effort subscription to the camera, and its images shown."""
    from rclpy.qos import ReliabilityPolicy

    s.kit('camera')
    windows = Path(s.temporary.name)
    s.student(
        'olive_camera',
        'display_camera',
        env=headless(windows),
    )
    info = s.expect_endpoint(
        CAMERA_TOPIC,
        'subscriptions',
        'sensor_msgs/msg/CompressedImage',
        f'no subscription on the camera topic {CAMERA_TOPIC}',
    )
    if info is not None:
        reliable = info.qos_profile.reliability == ReliabilityPolicy.RELIABLE
        s.add(
            Criterion(
                "the subscription's QoS matches the camera's BEST_EFFORT publisher",
                not reliable,
                (
                    'your subscription asks for RELIABLE (the default of a depth 10), but the camera offers '
                    'BEST_EFFORT, so no image ever arrives: subscribe with QoSProfile(depth=10, '
                    'reliability=QoSReliabilityPolicy.BEST_EFFORT, durability=QoSDurabilityPolicy.VOLATILE)'
                ),
                f'reliability {info.qos_profile.reliability.name}',
            )
        )
    matched = info is not None and info.qos_profile.reliability != ReliabilityPolicy.RELIABLE
    shown = matched and s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 10.0)
    s.add(
        Criterion(
            "cv2.imshow shows the camera's images",
            shown,
            (
                'no image reached cv2.imshow in 10 s: convert each message with '
                'CvBridge().compressed_imgmsg_to_cv2(msg) and pass it to cv2.imshow, then cv2.waitKey(1)'
            )
            if matched
            else 'no image can arrive while the QoS does not match',
        )
    )
    s.stop_student()


@SECTION.check(
    'robot_camera_launch',
    '4.5 +',
    'olive_camera',
    'a launch file that starts imu_control_robot and display_camera',
    extra=True,
)
def check_robot_camera_launch(s: Session) -> None:
    """Launch olive_camera's launch file: the IMU turns the head and the camera's images are shown."""
    from std_msgs.msg import Float32

    files = [
        f
        for f in launch_files('olive_camera')
        if 'imu_control_robot' in f.read_text() and 'display_camera' in f.read_text()
    ]
    if not s.add(
        Criterion(
            'olive_camera installs a launch file that names imu_control_robot and display_camera',
            bool(files),
            'a launch file in olive_camera/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files),
        )
    ):
        return
    s.kit('imu', 'pan', 'tilt', 'camera')  # the IMU's scripted motion turns the head
    pan = s.collect(Float32, goal_topic('pan'))
    windows = Path(s.temporary.name)
    s.student_launch(
        'olive_camera',
        files[0].name,
        env=headless(windows),
    )
    s.wait(lambda: len({round(m.data, 2) for _, m in pan}) >= 3, 20.0)
    s.add(
        Criterion(
            f'ros2 launch olive_camera {files[0].name}: imu_control_robot turns the head with the IMU',
            len({round(m.data, 2) for _, m in pan}) >= 3,
            'no changing pan goals arrived: the launch file must start olive_servo\'s imu_control_robot',
            f'{len(pan)} pan goals',
        )
    )
    shown = s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 15.0)
    s.add(
        Criterion(
            "ros2 launch ... : display_camera shows the camera's images",
            shown,
            "no image reached cv2.imshow: the launch file must start olive_camera's display_camera",
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)
