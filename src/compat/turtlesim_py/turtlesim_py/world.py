"""The turtlesim world: sizes, angle convention and the fixed-step kinematics, free of ROS.

Positions are kept the way upstream keeps them: x to the right and y *down* from the top edge
("internal" coordinates, in metres). World y (what every ROS interface shows) is HEIGHT - internal y.
"""

from __future__ import annotations

import math
import struct

# Upstream uses this truncated literal, so +pi itself normalizes to -pi.
PI = 3.14159265
TWO_PI = 2.0 * PI

CANVAS_PX = 500
METER_PX = 45  # the turtle images' height: one metre on the canvas
TICK_MS = 16
TICK_DT = 0.001 * TICK_MS
COMMAND_TIMEOUT = 1.0
# s: ticks a busy machine held back are made up, each at its own time, while they are at most this
# late, so one velocity command moves a turtle its 62-63 ticks (upstream's C++ node is rarely late;
# suite runs on two busy cores held ours back 0.3 s, twice)
TICK_CATCH_UP = 0.5


def tick_time(last_tick: float, now: float) -> float:
    """The time of the tick after the one at last_tick, when the clock reads now.

    That is its due time while it is at most TICK_CATCH_UP late (a made-up tick), else now (the
    clock jumped, stopped under sim time, or the ticks fell too far behind).
    """
    due = last_tick + TICK_DT
    return due if due <= now <= due + TICK_CATCH_UP else now


def float32(value: float) -> float:
    """Value rounded to the nearest IEEE single, as a C++ float would hold it."""
    return struct.unpack('f', struct.pack('f', value))[0]


# (500 - 1) / 45 computed in single precision, as upstream's float members do: 11.088889.
WIDTH = float32((CANVAS_PX - 1) / METER_PX)
HEIGHT = WIDTH
CENTER = float32(WIDTH / 2.0)


def normalize_angle(angle: float) -> float:
    """Angle wrapped into [-PI, PI)."""
    return angle - TWO_PI * math.floor((angle + PI) / TWO_PI)


def integrate(x: float, y_down: float, theta: float, vx: float, vy: float, omega: float,
              dt: float = TICK_DT) -> tuple[float, float, float]:
    """One semi-implicit Euler step: rotate first, then translate along the new heading.

    Works in internal coordinates (y down), so the world-frame y velocity is subtracted.
    """
    theta = normalize_angle(theta + omega * dt)
    cos_t, sin_t = math.cos(theta), math.sin(theta)
    x += (cos_t * vx - sin_t * vy) * dt
    y_down -= (sin_t * vx + cos_t * vy) * dt
    return x, y_down, theta


def outside_world(x: float, y_down: float) -> bool:
    """Whether an internal position lies beyond the walls (Turtle.update then warns and clamps it)."""
    return x < 0.0 or x > WIDTH or y_down < 0.0 or y_down > HEIGHT


def clamp_to_world(x: float, y_down: float) -> tuple[float, float]:
    """An internal position moved onto the nearest point inside the walls."""
    return min(max(x, 0.0), WIDTH), min(max(y_down, 0.0), HEIGHT)


def to_pixels(x: float, y_down: float) -> tuple[float, float]:
    """Canvas pixel coordinates (origin top-left) of an internal position."""
    return x * METER_PX, y_down * METER_PX


def nearest_pixel(x: float, y_down: float) -> tuple[int, int]:
    """The pixel a position falls on, rounded to nearest as Qt's QPointF::toPoint() does."""
    px, py = to_pixels(x, y_down)
    return _round_half_away(px), _round_half_away(py)


def _round_half_away(value: float) -> int:
    return math.floor(value + 0.5) if value >= 0 else -math.floor(-value + 0.5)
