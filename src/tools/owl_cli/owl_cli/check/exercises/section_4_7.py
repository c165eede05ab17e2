"""Section 4.7 (our text, docs/course): the head answers the gestures the camera's gesture app says."""

from __future__ import annotations

import time
from pathlib import Path

from olive_kit.description import GESTURE_TOPIC, goal_topic

from owl_cli.check.catalogue import Section
from owl_cli.check.kit_helpers import joint_positions, torque_criterion
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    CAMERA_NODE,
    Session,
    headless,
    launch_files,
)

SECTION = Section()

MOVED = 0.1    # rad: a head that moved at least this far answered the gesture
FACING = 0.05  # rad from the middle: facing the person again


def person_scene(gesture: str) -> dict[str, object]:
    """The camera's parameters for the person making a gesture."""
    return {'scene': 'person', 'gesture': gesture}


def farthest(joints: dict[str, list], since: float) -> float:
    """How far (rad) the head was from the middle at most, in the joint states from monotonic time since."""
    return max((abs(m.position[0]) for servo in joints.values() for t, m in servo
                if t >= since and m.position), default=0.0)


def facing(joints: dict[str, list]) -> bool:
    """Whether the head faces the person (both servos near 0)."""
    return all(servo and servo[-1][1].position and abs(servo[-1][1].position[0]) < FACING
               for servo in joints.values())


def answer_criteria(s: Session, joints: dict[str, list], gesture: str, words: str) -> None:
    """Make the person's gesture; add that the head moved, and that it came back to face them."""
    s.set_parameter(CAMERA_NODE, 'gesture', gesture)
    since = time.monotonic()
    s.wait(lambda: farthest(joints, since) > MOVED, 8.0)
    moved = farthest(joints, since)
    s.add(Criterion(
        f'the head answers a new gesture ({words}) with a motion',
        moved > MOVED,
        f'the head did not move after the gesture: subscribe to {GESTURE_TOPIC} and send pan/tilt goals '
        'when a new label arrives',
        f'{moved:.2f} rad at most'))
    if moved > MOVED:
        back = s.wait(lambda: facing(joints), 10.0)
        s.add(Criterion(
            f'after answering {words}, the head faces the person again (pan and tilt back to 0)',
            back,
            'the head stays turned away: the camera then cannot see the next gesture; end each motion '
            'at pan 0, tilt 0 (and act only on a new label, as the app repeats its last one)'))


@SECTION.check(
    'gesture_control',
    '4.7',
    'olive_vision',
    "answers each new gesture on the camera's tpu/gesture with a head motion that ends facing the person",
)
def check_gesture_control(s: Session) -> None:
    """Run gesture_control; the person raises both hands, then puts them on the hips."""
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt', 'camera', scene=person_scene('both_hands_down'))
    joints = {servo: joint_positions(s, servo) for servo in ('pan', 'tilt')}
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    s.student('olive_vision', 'gesture_control')
    if s.expect_endpoint(GESTURE_TOPIC, 'subscriptions', 'std_msgs/msg/String',
                         f"no subscription on the gesture app's topic {GESTURE_TOPIC}") is None:
        s.stop_student()
        return
    s.wait(lambda: facing(joints), 5.0)
    answer_criteria(s, joints, 'both_hands_up', 'both hands up')
    answer_criteria(s, joints, 'hands_on_hip', 'hands on hip')
    for servo in ('pan', 'tilt'):
        if goals[servo]:
            torque_criterion(s, servo, goals[servo])
    s.stop_student()


@SECTION.check(
    'gesture_control_turtle',
    '4.7 +',
    'olive_vision',
    'with target:=turtle, the gestures drive turtlesim\'s turtle',
    extra=True,
)
def check_gesture_control_turtle(s: Session) -> None:
    """Run gesture_control -p target:=turtle beside turtlesim; the person raises both hands."""
    from turtlesim.msg import Pose

    s.helper('turtlesim', 'turtlesim_node', '--headless')
    poses = s.collect(Pose, '/turtle1/pose')
    s.kit('camera', scene=person_scene('both_hands_down'))
    s.student('olive_vision', 'gesture_control', '--ros-args', '-p', 'target:=turtle')
    s.expect_endpoint('/turtle1/cmd_vel', 'publishers', 'geometry_msgs/msg/Twist',
                      'no publisher on /turtle1/cmd_vel: with target:=turtle, drive the turtle, not the head')
    s.set_parameter(CAMERA_NODE, 'gesture', 'both_hands_up')
    since = time.monotonic()

    def driven() -> bool:
        moving = [m for t, m in poses if t >= since and (m.linear_velocity or m.angular_velocity)]
        return bool(moving)

    s.add(Criterion(
        'a gesture (both hands up) moves the turtle', s.wait(driven, 10.0),
        'the turtle did not move: publish a Twist on /turtle1/cmd_vel for each gesture label'))
    s.stop_student()


@SECTION.check(
    'gesture_control_launch',
    '4.7 +',
    'olive_vision',
    "a launch file that starts gesture_control and display_camera (the gesture app's picture)",
    extra=True,
)
def check_gesture_control_launch(s: Session) -> None:
    """Launch olive_vision's launch file: the head answers a gesture and the app's picture is shown."""
    files = [f for f in launch_files('olive_vision')
             if 'gesture_control' in f.read_text() and 'display_camera' in f.read_text()]
    if not s.add(Criterion(
            'olive_vision installs a launch file that names gesture_control and display_camera', bool(files),
            'a launch file in olive_vision/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files))):
        return
    s.kit('pan', 'tilt', 'camera', scene=person_scene('both_hands_down'))
    joints = {servo: joint_positions(s, servo) for servo in ('pan', 'tilt')}
    windows = Path(s.temporary.name)
    s.student_launch('olive_vision', files[0].name, env=headless(windows))
    s.wait(lambda: s.endpoints(GESTURE_TOPIC, 'subscriptions') != [], 20.0)
    s.set_parameter(CAMERA_NODE, 'gesture', 'both_hands_up')
    since = time.monotonic()
    s.add(Criterion(
        f'ros2 launch olive_vision {files[0].name}: gesture_control answers a gesture',
        s.wait(lambda: farthest(joints, since) > MOVED, 10.0),
        "the head did not move: the launch file must start olive_vision's gesture_control"))
    s.add(Criterion(
        "ros2 launch ... : display_camera shows the gesture app's picture",
        s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 15.0),
        "no image reached cv2.imshow: the launch file must start olive_camera's display_camera"))
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)
