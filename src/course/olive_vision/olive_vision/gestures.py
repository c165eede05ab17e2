"""What the head does for each gesture the camera's gesture app recognises: no ROS.

The app (a vendor example on the camera's TPU) publishes a label on tpu/gesture for the last
gesture it recognised: the digits 1-7 in the order of the vendor's list, 'none' before the first.
The head answers a new gesture with a short motion and comes back to face the person, who must stay
in sight to be seen making the next one.
"""

from dataclasses import dataclass

# label -> (the gesture in words, the motion that answers it)
GESTURES = {
    '1': ('both hands down', 'rest'),
    '2': ('both hands up', 'nod'),
    '3': ('left down / right up', 'look_left'),   # the person's right hand is on the robot's left
    '4': ('right down / left up', 'look_right'),
    '5': ('left down / right side', 'look_left'),
    '6': ('right down / left side', 'look_right'),
    '7': ('hands on hip', 'shake'),
}
NO_GESTURE = 'none'

# Each motion: (pan, tilt) goals in rad, each held for STEP s, then back to the middle.
STEP = 0.4
MOTIONS = {
    'rest': [(0.0, 0.0)],
    'nod': [(0.0, 0.3), (0.0, -0.1), (0.0, 0.3), (0.0, 0.0)],
    'shake': [(0.3, 0.0), (-0.3, 0.0), (0.3, 0.0), (0.0, 0.0)],
    'look_left': [(0.35, 0.0), (0.35, 0.0), (0.0, 0.0)],
    'look_right': [(-0.35, 0.0), (-0.35, 0.0), (0.0, 0.0)],
}


def words(label: str) -> str:
    """The gesture of a label in words, e.g. 'both hands up'; the label itself if unknown."""
    return GESTURES[label][0] if label in GESTURES else label


@dataclass
class MotionPlayer:
    """Plays a motion's goals one STEP after the other; idle once the last one has been held."""

    goals: list[tuple[float, float]]
    started: float

    def goal(self, now: float) -> tuple[float, float] | None:
        """The (pan, tilt) goal at time now, or None when the motion is over."""
        index = int((now - self.started) / STEP)
        return self.goals[index] if 0 <= index < len(self.goals) else None
