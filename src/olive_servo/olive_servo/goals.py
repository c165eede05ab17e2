"""Goal positions for the servos, kept free of ROS: the sine, the bounds, the IMU's head angles."""

import math

# The Owl Kit's ranges in rad: pan turns the head +-90 deg, tilt carries the camera from -1.3 rad
# (looking up) to 0.9 rad (looking down), the vendor demos' range and olive_sim's owl_kit launch.
PAN_BOUNDS = (-1.5708, 1.5708)
TILT_BOUNDS = (-1.3, 0.9)
# The widest range any bound may take: one turn of the servo's output.
BOUND_LIMIT = math.pi


def clamp(value: float, low: float, high: float) -> float:
    """value limited to low..high."""
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
