"""Goal positions for the servos, kept free of ROS.

The sine, the bounds, the IMU's head angles, the arrow keys' goals.
"""

import math

# The Owl Kit's ranges in rad: pan turns the head +-90 deg, tilt carries the camera from -1.3 rad
# (looking up) to 0.9 rad (looking down), the vendor demos' range and olive_sim's owl_kit launch.
PAN_BOUNDS = (-1.5708, 1.5708)
TILT_BOUNDS = (-1.3, 0.9)
# The widest range any bound may take: one turn of the servo's output.
BOUND_LIMIT = math.pi
KIT_BOUNDS = {'pan': PAN_BOUNDS, 'tilt': TILT_BOUNDS}


def clamp(value: float, low: float, high: float) -> float:
    """Value limited to low..high."""
    return max(low, min(high, value))


def bounds_problem(name: str, low: float, high: float) -> str | None:
    """Why low..high cannot be a servo's goal range, or None when it can."""
    if not low < high:
        return f'{name}_min ({low}) must be less than {name}_max ({high})'
    return None


class SineGoal:
    """The course's sine: a phase that grows by `step` rad per goal, and amplitude * sin(phase)."""

    def __init__(self, step: float) -> None:
        self.step = step
        self.phase = 0.0

    def next(self, amplitude: float) -> float:
        goal = amplitude * math.sin(self.phase)
        self.phase = (self.phase + self.step) % (2 * math.pi)  # stays small, so sin stays exact
        return goal


def head_goals(pitch: float, yaw: float, pan_bounds: tuple[float, float],
               tilt_bounds: tuple[float, float]) -> tuple[float, float]:
    """(pan, tilt) goals that point the head where the IMU points, each within its bounds.

    Turning the IMU left (positive yaw) turns the pan servo left (positive pan); tilting it forward,
    nose down (positive pitch), tilts the camera down (positive tilt).
    """
    return clamp(yaw, *pan_bounds), clamp(pitch, *tilt_bounds)


# Which servo each arrow key moves, and which way (REP 103: positive pan turns the head left,
# counter-clockwise seen from above; positive tilt turns the camera down). Each arrow moves the
# camera's view the way it points: Left looks left, Up looks up.
ARROW_KEYS = {
    'left': ('pan', +1),
    'right': ('pan', -1),
    'up': ('tilt', -1),
    'down': ('tilt', +1),
}
# s: the longest time one step may cover, so a stalled timer (a busy machine, a dragged window)
# cannot make the goal jump when it runs again.
MAX_STEP_TIME = 0.1


def key_directions(held: set[str]) -> dict[str, int]:
    """-1, 0 or +1 for each servo, from the held arrow keys' names; opposite arrows cancel."""
    directions = {'pan': 0, 'tilt': 0}
    for key in held:
        if key in ARROW_KEYS:
            servo, sign = ARROW_KEYS[key]
            directions[servo] += sign
    return directions


class KeyboardGoals:
    """The pan and tilt goals that the held arrow keys move at `speed` rad/s, each within its bounds.

    Both start at the head's centre (0 rad) or the bound nearest to it.
    """

    def __init__(self) -> None:
        self.goals = {'pan': 0.0, 'tilt': 0.0}

    def advance(self, held: set[str], speed: float, elapsed: float,
                bounds: dict[str, tuple[float, float]]) -> dict[str, float]:
        """Move the goals for `elapsed` s of the held keys; return the new goals.

        A goal outside its bounds (bounds narrowed at runtime) is brought back within them even
        when no key is held.
        """
        step = speed * min(max(elapsed, 0.0), MAX_STEP_TIME)
        for servo, direction in key_directions(held).items():
            self.goals[servo] = clamp(self.goals[servo] + direction * step, *bounds[servo])
        return dict(self.goals)
