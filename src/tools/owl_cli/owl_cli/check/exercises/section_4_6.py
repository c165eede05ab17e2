"""Section 4.6 (our text, docs/course): the head tracks the red ball the camera sees."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

from olive_kit.description import CAMERA_TOPIC, goal_topic

from owl_cli.check import criteria as judge
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

# The still ball: left of the middle and below it, in sight of the camera at rest. The head points
# at a direction (azimuth, elevation) with pan = azimuth and tilt = -elevation.
BALL = (0.3, -0.1)
CENTRED = 0.03      # rad off the ball: 3 % of the image's width
FOLLOWING = 0.1     # rad off the moving ball
MOVING_SPEED = 0.2  # rad/s
HIDDEN_BALL = (1.2, -0.05)  # out of sight at rest: only a search finds it
# s after the ball set off: the head must follow it from FOLLOW_FROM to FOLLOW_UNTIL.
FOLLOW_FROM, FOLLOW_UNTIL = 1.5, 5.0
# A head that has stood still this long away from a still ball has stopped there: a tracker sends
# goals from every image (30 a second), so one that moves the head at all keeps it moving until it
# aims. The verdict comes then rather than at the 15 s limit. Not before GRACE s after the tracker
# subscribed, so one that starts slowly (its first image, its imports) gets its time.
STILL_FOR, STILL_WITHIN, GRACE = 2.0, 0.002, 4.0  # s, rad, s


def stamp_seconds(message: Any) -> float:
    """A stamped message's header stamp, in seconds of the wall clock."""
    stamp = message.header.stamp
    return stamp.sec + stamp.nanosec * 1e-9


def ball_scene(azimuth: float, elevation: float) -> dict[str, object]:
    """The camera's parameters for a still ball in that direction."""
    return {'scene': 'ball', 'ball_speed': 0.0, 'ball_azimuth': azimuth, 'ball_elevation': elevation}


def last_position(joints: list) -> float | None:
    """The servo's last position from its joint states (Session.collect pairs), None before one."""
    return joints[-1][1].position[0] if joints and joints[-1][1].position else None


def near(joints: list, value: float, tolerance: float) -> bool:
    """Whether the servo's last position is within tolerance of value."""
    position = last_position(joints)
    return position is not None and abs(position - value) < tolerance


def stopped_short(joints: dict[str, list], since: float, now: float) -> bool:
    """Whether every servo's joint states of the last STILL_FOR s stayed within STILL_WITHIN rad.

    since: when the tracker subscribed (monotonic); before since + GRACE nothing has stopped yet.
    """
    if now - since < GRACE:
        return False
    for received in joints.values():
        recent = [m.position[0] for t, m in received if t >= now - STILL_FOR and m.position]
        if not recent or max(recent) - min(recent) > STILL_WITHIN:
            return False
    return True


def lags_behind_moving_ball(pan: list, left_between: tuple[float, float]) -> list[float]:
    """How far the pan servo was from the ball going round, in each of its joint states of the window.

    left_between: the wall-clock times between which the ball set off at MOVING_SPEED from BALL. The
    window is FOLLOW_FROM to FOLLOW_UNTIL s after that, by the joint states' stamps (when the servo
    measured), not by when they arrived here: on a busy machine this checker can get them in a burst,
    late, which is not the tracker's lag.
    """
    after = left_between[1]
    return [judge.lag_behind_moving_target(m.position[0], measured, BALL[0], MOVING_SPEED, left_between)
            for measured, m in ((stamp_seconds(m), m) for _, m in pan)
            if after + FOLLOW_FROM <= measured <= after + FOLLOW_UNTIL and m.position]


def fell_behind(pan: list, left_between: tuple[float, float]) -> bool:
    """Whether a joint state of the window already lags FOLLOWING or more: the head does not follow.

    Later joint states only add lags, so no more of the window can make it follow.
    """
    return max(lags_behind_moving_ball(pan, left_between), default=0.0) >= FOLLOWING


def aim_criterion(s: Session, servo: str, joints: list, wanted: float) -> bool:
    """Add the criterion that a servo points the camera at the ball, with a hint for each wrong way."""
    position = last_position(joints)
    way = {'pan': 'left' if wanted > 0 else 'right', 'tilt': 'down' if wanted > 0 else 'up'}[servo]
    if position is None:
        hint = f'no joint state of the {servo} servo arrived'
    elif position * wanted < 0 and abs(position) > CENTRED:
        hint = (f'the {servo} servo turns away from the ball: positive pan turns the head left and '
                'positive tilt turns the camera down, so a ball left of the middle needs a larger pan goal '
                'and a ball below it a larger tilt goal; check the sign')
    elif abs(position) < CENTRED:
        hint = (f'the {servo} servo does not follow the ball: compute the ball\'s angle '
                f"{'right of' if servo == 'pan' else 'below'} the middle and send {servo} goals from it")
    else:
        hint = (f'the {servo} servo stops {abs(position - wanted):.2f} rad from the ball: point it where the '
                f'ball is (its position plus the ball\'s angle from the middle)')
    return s.add(Criterion(
        f'the {servo} servo points the camera at the still ball ({way}, to {wanted:+.2f} rad)',
        near(joints, wanted, CENTRED), hint,
        'no position' if position is None else f'at {position:+.3f} rad'))


@SECTION.check(
    'track_object',
    '4.6',
    'olive_vision',
    'finds the red ball in the camera images and points the pan/tilt head at it, still or moving',
)
def check_track_object(s: Session) -> None:
    """Run track_object against a still, then a moving ball: the head points at it and follows it."""
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt', 'camera', scene=ball_scene(*BALL))
    joints = {servo: joint_positions(s, servo) for servo in ('pan', 'tilt')}
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    s.student('olive_vision', 'track_object')
    if s.expect_endpoint(CAMERA_TOPIC, 'subscriptions', 'sensor_msgs/msg/CompressedImage',
                         f'no subscription on the camera topic {CAMERA_TOPIC}') is None:
        s.stop_student()
        return
    wanted = {'pan': BALL[0], 'tilt': -BALL[1]}
    subscribed = time.monotonic()
    s.wait(lambda: all(near(joints[servo], wanted[servo], CENTRED) for servo in wanted)
           or stopped_short(joints, subscribed, time.monotonic()), 15.0)
    for servo in ('pan', 'tilt'):
        torque_criterion(s, servo, goals[servo])
    aimed = all([aim_criterion(s, servo, joints[servo], wanted[servo]) for servo in ('pan', 'tilt')])
    if aimed:
        before = time.time()
        s.set_parameter(CAMERA_NODE, 'ball_speed', MOVING_SPEED)
        after = time.time()
        # Not Session.wait, which returns when the tracker ends: the head it leaves standing is still
        # judged over the whole window.
        deadline = time.monotonic() + FOLLOW_UNTIL
        while time.monotonic() < deadline and not fell_behind(joints['pan'], (before, after)):
            time.sleep(0.05)
        lag = lags_behind_moving_ball(joints['pan'], (before, after))
        s.add(Criterion(
            f'the head follows the ball going round at {MOVING_SPEED} rad/s '
            f'(pan within {FOLLOWING} rad of it)',
            bool(lag) and max(lag) < FOLLOWING,
            'the head falls behind or loses the ball: send new goals from every image, from where the '
            'servos are now (their joint states)',
            f'at most {max(lag):.3f} rad off' if lag else 'no joint states'))
    s.stop_student()


@SECTION.check(
    'track_object_search',
    '4.6 +',
    'olive_vision',
    'with search:=true, sweeps the pan servo until it finds a ball out of sight',
    extra=True,
)
def check_track_object_search(s: Session) -> None:
    """Run track_object -p search:=true with the ball out of sight: the head finds it and points at it."""
    s.kit('pan', 'tilt', 'camera', scene=ball_scene(*HIDDEN_BALL))
    pan = joint_positions(s, 'pan')
    s.student('olive_vision', 'track_object', '--ros-args', '-p', 'search:=true')
    found = s.wait(lambda: near(pan, HIDDEN_BALL[0], CENTRED), 30.0)
    position = last_position(pan)
    s.add(Criterion(
        f'finds the ball {HIDDEN_BALL[0]} rad to the left, out of sight at the start, and points at it',
        found,
        'the head never found the ball: when no red ball has been seen for a second, send pan goals that '
        'sweep from side to side (parameter search, true), and track it again once it is in sight',
        'no position' if position is None else f'pan at {position:+.3f} rad'))
    s.stop_student()


@SECTION.check(
    'track_object_launch',
    '4.6 +',
    'olive_vision',
    'a launch file that starts track_object and display_camera',
    extra=True,
)
def check_track_object_launch(s: Session) -> None:
    """Launch olive_vision's launch file: the head points at the ball and the camera's images are shown."""
    files = [f for f in launch_files('olive_vision')
             if 'track_object' in f.read_text() and 'display_camera' in f.read_text()]
    if not s.add(Criterion(
            'olive_vision installs a launch file that names track_object and display_camera', bool(files),
            'a launch file in olive_vision/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files))):
        return
    s.kit('pan', 'tilt', 'camera', scene=ball_scene(*BALL))
    pan = joint_positions(s, 'pan')
    windows = Path(s.temporary.name)
    s.student_launch('olive_vision', files[0].name, env=headless(windows))
    s.add(Criterion(
        f'ros2 launch olive_vision {files[0].name}: track_object points the head at the ball',
        s.wait(lambda: near(pan, BALL[0], CENTRED), 20.0),
        "the pan servo did not turn to the ball: the launch file must start olive_vision's track_object"))
    s.add(Criterion(
        "ros2 launch ... : display_camera shows the camera's images",
        s.wait(lambda: any(windows.glob('*/cv2-*.jpg')), 15.0),
        "no image reached cv2.imshow: the launch file must start olive_camera's display_camera"))
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)
