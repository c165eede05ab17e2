"""Orientation quaternions to Euler angles with the course's equations (3), kept free of ROS."""

import math
from collections.abc import Sequence
from typing import Protocol

# Shorter than this, a quaternion has no direction left to normalise (a zero quaternion).
MIN_NORM = 1e-6


class QuaternionLike(Protocol):
    """Anything with x, y, z, w, such as geometry_msgs/msg/Quaternion."""

    x: float
    y: float
    z: float
    w: float


def orientation_problem(q: QuaternionLike, covariance: Sequence[float] = (0.0,)) -> str | None:
    """Why an IMU orientation cannot be used, or None when it can.

    sensor_msgs/msg/Imu says a -1 as the first element of orientation_covariance means the IMU
    has no orientation estimate; a non-finite or zero quaternion is no rotation at all.
    """
    if len(covariance) > 0 and covariance[0] == -1.0:  # a message's array is numpy's
        return 'the IMU reports no orientation (orientation_covariance[0] is -1)'
    components = (q.x, q.y, q.z, q.w)
    if not all(math.isfinite(c) for c in components):
        return f'the orientation quaternion {components} is not finite'
    if math.sqrt(sum(c * c for c in components)) < MIN_NORM:
        return 'the orientation quaternion is zero, not a rotation'
    return None


def quaternion_to_euler(q: QuaternionLike) -> tuple[float, float, float]:
    """(roll, pitch, yaw) in radians of a usable quaternion (see orientation_problem).

    The equations hold for unit quaternions, so q is scaled to unit length first.
    """
    norm = math.sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w)
    x, y, z, w = q.x / norm, q.y / norm, q.z / norm, q.w / norm
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    # Rounding can push the sine of the pitch just past +-1, where asin is undefined.
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw
