"""The arrow keys' drive, shared by turtle_teleop_key (a terminal) and the browser window (a page).

Each arrow asks for a speed in multiples of the teleop's scales (2.0 m/s and 2.0 rad/s by default,
upstream's): up forward, down back, left turns counter-clockwise, right clockwise.
"""

from __future__ import annotations

from collections.abc import Iterable

DEFAULT_SCALE = 2.0  # turtle_teleop_key's scale_linear and scale_angular defaults
# pygame's key name -> (linear, angular) in multiples of the scales
ARROWS = {'up': (1.0, 0.0), 'down': (-1.0, 0.0), 'right': (0.0, -1.0), 'left': (0.0, 1.0)}


def held_drive(held: Iterable[str], scale_linear: float = DEFAULT_SCALE,
               scale_angular: float = DEFAULT_SCALE) -> tuple[float, float] | None:
    """(linear, angular) speeds for the arrow keys held down together; None when no arrow is held.

    Opposite arrows cancel each other; up and left together drive a left curve.
    """
    arrows = [ARROWS[key] for key in set(held) if key in ARROWS]
    if not arrows:
        return None
    return (scale_linear * sum(linear for linear, _ in arrows),
            scale_angular * sum(angular for _, angular in arrows))
