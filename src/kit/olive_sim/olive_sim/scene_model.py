"""What stands around the robot besides the panorama: a red ball and a person, as directions.

Directions are (azimuth, elevation) in rad in the robot's frame, as the panorama's (azimuth 0
straight ahead at pan 0, growing to the left; elevation 0 at the horizon, up positive). The
camera turns by pan about the vertical and looks down by tilt (camera_render's convention);
project() turns a direction into the pixel where a pinhole camera at that pan and tilt sees it.
No ROS, no drawing: camera_render draws what this module places.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

SCENES = ('landmarks', 'ball', 'person')

BALL_START = (0.25, -0.12)  # rad: left of and below the centre of the camera at rest, in sight
BALL_RADIUS = 0.035         # rad: a 7 cm ball 1 m away
BALL_BOB = 0.08             # rad: how far the ball's path rises and falls as it goes round
BALL_BOBS_PER_TURN = 3      # rises and falls per turn around the robot
BALL_MAX_SPEED = 2.0        # rad/s along its path: more than the head can follow
BALL_MAX_SWING = math.pi    # rad to either side of its middle: a swing of pi is a whole circle
# Where a ball may be put: in front of the camera's whole tilt range, not under the robot.
BALL_ELEVATION_RANGE = (-0.6, 0.6)

# A person standing 3.5 m in front of the robot, the camera at their hip height: keypoints as
# (metres to the person's left seen from the robot, metres up from the camera), 17 of them in the
# order and with the names of the PoseNet model the camera's example app runs (COCO keypoints).
PERSON_DISTANCE = 3.5       # m
PERSON_AZIMUTH = 0.0        # rad: straight ahead at pan 0
KEYPOINTS = ('nose', 'left_eye', 'right_eye', 'left_ear', 'right_ear', 'left_shoulder', 'right_shoulder',
             'left_elbow', 'right_elbow', 'left_wrist', 'right_wrist', 'left_hip', 'right_hip',
             'left_knee', 'right_knee', 'left_ankle', 'right_ankle')
# The skeleton's bones, as the example app draws them between keypoints.
BONES = (('nose', 'left_eye'), ('nose', 'right_eye'), ('left_ear', 'left_eye'), ('right_ear', 'right_eye'),
         ('left_eye', 'right_eye'), ('left_shoulder', 'right_shoulder'), ('left_shoulder', 'left_elbow'),
         ('left_shoulder', 'left_hip'), ('right_shoulder', 'right_elbow'), ('right_shoulder', 'right_hip'),
         ('left_elbow', 'left_wrist'), ('right_elbow', 'right_wrist'), ('left_hip', 'right_hip'),
         ('left_hip', 'left_knee'), ('right_hip', 'right_knee'), ('left_knee', 'left_ankle'),
         ('right_knee', 'right_ankle'))

# The body without its arms, facing the robot: the person's left is the robot's right (negative y).
_BODY = {
    'nose': (0.0, 0.62), 'left_eye': (-0.035, 0.66), 'right_eye': (0.035, 0.66),
    'left_ear': (-0.075, 0.64), 'right_ear': (0.075, 0.64),
    'left_shoulder': (-0.20, 0.45), 'right_shoulder': (0.20, 0.45),
    'left_hip': (-0.12, 0.0), 'right_hip': (0.12, 0.0),
    'left_knee': (-0.13, -0.45), 'right_knee': (0.13, -0.45),
    'left_ankle': (-0.13, -0.88), 'right_ankle': (0.13, -0.88),
}
# Each arm's pose: (elbow, wrist) relative to its shoulder, for the person's left arm (mirrored
# for the right one). "side": stretched out sideways; "hip": hands on the hips.
_ARM = {
    'down': ((-0.03, -0.28), (-0.05, -0.55)),
    'up': ((-0.05, 0.28), (-0.06, 0.56)),
    'side': ((-0.28, 0.0), (-0.56, 0.0)),
    'hip': ((-0.22, -0.20), (0.05, -0.42)),
}


@dataclass(frozen=True)
class Gesture:
    """One gesture of the camera's gesture app: its label on tpu/gesture and the arms' poses."""

    label: str
    name: str
    left_arm: str   # the person's own left
    right_arm: str

    @property
    def words(self) -> str:
        """The gesture as the vendor's README says it, e.g. 'left down / right up'."""
        return self.name.replace('_', ' ')


# The seven gestures the vendor's example app is trained on, in the order of its README. Their
# labels on tpu/gesture are the classifier's classes, the digits 1-7 (its training data labels
# gestures with digits; which digit is which gesture is not published: this order is our reading).
GESTURES = (
    Gesture('1', 'both_hands_down', 'down', 'down'),
    Gesture('2', 'both_hands_up', 'up', 'up'),
    Gesture('3', 'left_down_right_up', 'down', 'up'),
    Gesture('4', 'right_down_left_up', 'up', 'down'),
    Gesture('5', 'left_down_right_side', 'down', 'side'),
    Gesture('6', 'right_down_left_side', 'side', 'down'),
    Gesture('7', 'hands_on_hip', 'hip', 'hip'),
)
GESTURE_NAMES = tuple(g.name for g in GESTURES)
NO_GESTURE = 'none'  # what the app publishes before it has recognised any gesture


def gesture_named(name: str) -> Gesture:
    """The gesture of this name; ValueError naming the known ones otherwise."""
    for gesture in GESTURES:
        if gesture.name == name:
            return gesture
    raise ValueError(f"unknown gesture '{name}': expected one of {', '.join(GESTURE_NAMES)}")


def person_pose(gesture: Gesture) -> dict[str, tuple[float, float]]:
    """The person's 17 keypoints as (m to the robot's left, m up) for a gesture."""
    points = dict(_BODY)
    for side, pose, sign in (('left', gesture.left_arm, 1.0), ('right', gesture.right_arm, -1.0)):
        shoulder_y, shoulder_z = points[f'{side}_shoulder']
        for joint, (dy, dz) in zip(('elbow', 'wrist'), _ARM[pose], strict=True):
            points[f'{side}_{joint}'] = (shoulder_y + sign * dy, shoulder_z + dz)
    return {name: points[name] for name in KEYPOINTS}


def person_directions(gesture: Gesture) -> dict[str, tuple[float, float]]:
    """The person's keypoints as directions (azimuth, elevation) from the camera."""
    return {name: (PERSON_AZIMUTH + math.atan2(y, PERSON_DISTANCE), math.atan2(z, PERSON_DISTANCE))
            for name, (y, z) in person_pose(gesture).items()}


@dataclass
class BallPath:
    """The ball going round the robot at speed rad/s of azimuth, rising and falling as it goes.

    It starts at (azimuth, elevation) at time start (s, any clock); speed 0 keeps it there. With a
    swing (rad), it goes to and fro about that azimuth instead, swing to either side, at speed rad/s
    where it passes the middle: a ball the pan servo can follow the whole time. phase: where in its
    swing it is at start (rad of the swing's sine; 0 is the middle, moving left).
    """

    azimuth: float
    elevation: float
    speed: float = 0.0
    start: float = 0.0
    swing: float = 0.0
    phase: float = 0.0

    def at(self, t: float) -> tuple[float, float]:
        """(azimuth, elevation) at time t."""
        travelled = self.speed * max(0.0, t - self.start)
        bob = BALL_BOB * math.sin(BALL_BOBS_PER_TURN * travelled)
        elevation = clamp_elevation(self.elevation + bob)
        if self.swing > 0.0:
            return wrap(self.azimuth + self.swing * math.sin(self._phase_at(t))), elevation
        return wrap(self.azimuth + travelled), elevation

    def _phase_at(self, t: float) -> float:
        return self.phase + self.speed * max(0.0, t - self.start) / self.swing

    def moved(self, t: float, *, azimuth: float | None = None, elevation: float | None = None,
              speed: float | None = None, swing: float | None = None) -> BallPath:
        """The path from where the ball is at t, with a new place, speed or swing if given.

        A swinging ball keeps its middle and its place in the swing when only its speed or
        elevation changes; a new place is the new middle; a new swing is about where it is.
        """
        here_azimuth, here_elevation = self.at(t)
        new_swing = self.swing if swing is None else swing
        keeps_swing = new_swing > 0.0 and swing is None and azimuth is None and self.swing > 0.0
        return BallPath(self.azimuth if keeps_swing else here_azimuth if azimuth is None else azimuth,
                        here_elevation if elevation is None else elevation,
                        self.speed if speed is None else speed, t, new_swing,
                        self._phase_at(t) if keeps_swing else 0.0)


def wrap(angle: float) -> float:
    """The angle wrapped into (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2 * math.pi)


def clamp_elevation(elevation: float) -> float:
    """The elevation limited to the ball's world, BALL_ELEVATION_RANGE."""
    low, high = BALL_ELEVATION_RANGE
    return min(high, max(low, elevation))


@dataclass(frozen=True)
class Pinhole:
    """A camera of focal lengths fx, fy and centre cx, cy (px) on the pan/tilt head."""

    fx: float
    fy: float
    cx: float
    cy: float

    def project(self, azimuth: float, elevation: float, pan: float, tilt: float
                ) -> tuple[float, float] | None:
        """The pixel (u right, v down) where the camera at pan, tilt sees a direction; None if behind it."""
        relative = azimuth - pan
        forward = math.cos(elevation) * math.cos(relative)
        left = math.cos(elevation) * math.sin(relative)
        up = math.sin(elevation)
        # Undo the tilt (a pitch down about the left axis).
        c, s = math.cos(tilt), math.sin(tilt)
        x = c * forward - s * up
        z = s * forward + c * up
        if x <= 1e-6:
            return None
        return self.cx - self.fx * left / x, self.cy - self.fy * z / x

    def direction(self, u: float, v: float, pan: float, tilt: float) -> tuple[float, float]:
        """The direction (azimuth, elevation) the pixel (u, v) looks at: project()'s inverse."""
        left, up = (self.cx - u) / self.fx, (self.cy - v) / self.fy
        c, s = math.cos(tilt), math.sin(tilt)
        forward, lifted = c + s * up, c * up - s
        return wrap(pan + math.atan2(left, forward)), math.atan2(lifted, math.hypot(forward, left))
