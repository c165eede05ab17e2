"""Unit quaternions as (x, y, z, w) tuples, the order of geometry_msgs/Quaternion.

The one quaternion module of our Python code (the simulator, robot_view, owl check, the demo). The
course's own packages keep their own conversion (olive_imu/euler.py), as a student writes it.
"""

from __future__ import annotations

import math

Quaternion = tuple[float, float, float, float]
Vector = tuple[float, float, float]

IDENTITY: Quaternion = (0.0, 0.0, 0.0, 1.0)


def multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    """The Hamilton product a * b: the rotation b, then a, both about the fixed axes."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def conjugate(q: Quaternion) -> Quaternion:
    """Q with x, y and z negated: for a unit quaternion, the inverse rotation."""
    return (-q[0], -q[1], -q[2], q[3])


def normalize(q: Quaternion) -> Quaternion:
    """Q scaled to unit length; ValueError for a zero or non-finite quaternion."""
    norm = math.sqrt(sum(c * c for c in q))
    if not math.isfinite(norm) or norm < 1e-9:
        raise ValueError(f'not a rotation: quaternion {q} has no usable length')
    return (q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm)


def from_euler(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Rotation yaw about z, then pitch about the new y, then roll about the new x (ROS RPY)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy)


def to_euler(q: Quaternion) -> Vector:
    """(roll, pitch, yaw) by the course's formulas (section 4.3.2)."""
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def usable_euler(q: Quaternion) -> Vector | None:
    """(roll, pitch, yaw) of q scaled to unit length, or None when q is zero or not finite."""
    try:
        return to_euler(normalize(q))
    except ValueError:
        return None


def rotate(q: Quaternion, v: Vector) -> Vector:
    """V expressed in the fixed frame, for v given in the frame that q rotates to."""
    x, y, z, _ = multiply(multiply(q, (v[0], v[1], v[2], 0.0)), conjugate(q))
    return x, y, z


def from_rotation_vector(r: Vector) -> Quaternion:
    """The rotation by |r| rad about the direction of r (as a gyro reading times its time step)."""
    angle = math.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2)
    if angle < 1e-12:
        return (r[0] / 2, r[1] / 2, r[2] / 2, 1.0)
    s = math.sin(angle / 2) / angle
    return (r[0] * s, r[1] * s, r[2] * s, math.cos(angle / 2))


def to_rotation_vector(q: Quaternion) -> Vector:
    """Q's axis scaled by its angle in rad, the short way round (angle at most pi)."""
    x, y, z, w = q
    if w < 0:  # the short way round
        x, y, z, w = -x, -y, -z, -w
    sin_half = math.sqrt(x * x + y * y + z * z)
    if sin_half < 1e-12:
        return (2 * x, 2 * y, 2 * z)
    angle = 2 * math.atan2(sin_half, w)
    return (x / sin_half * angle, y / sin_half * angle, z / sin_half * angle)


def angle_between(a: Quaternion, b: Quaternion) -> float:
    """The angle in rad (0 to pi) of the rotation that turns a into b."""
    r = to_rotation_vector(multiply(conjugate(a), b))
    return math.sqrt(r[0] ** 2 + r[1] ** 2 + r[2] ** 2)


def slerp(a: Quaternion, b: Quaternion, fraction: float) -> Quaternion:
    """The rotation `fraction` of the way from a to b along the shortest arc."""
    step = to_rotation_vector(multiply(conjugate(a), b))
    return multiply(a, from_rotation_vector((step[0] * fraction, step[1] * fraction, step[2] * fraction)))
