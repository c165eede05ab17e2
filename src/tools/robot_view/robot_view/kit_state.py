"""What the robot view shows of the kit, as plain data (node-free).

The joint angles and the IMU's orientation, and the commands a page may send to hold the
simulated IMU.
"""

from __future__ import annotations

from typing import Any

from owl_web import codec

LEVEL = (0.0, 0.0, 0.0, 1.0)  # x, y, z, w: the IMU lying flat, pointing along base_link's x


def hold_imu_orientation(arguments: dict[str, Any]) -> tuple[float, float, float, float]:
    """The orientation of a page's "hold_imu" command ({"orientation": {x, y, z, w}})."""
    codec.check_keys(arguments, ('orientation',), required=('orientation',))
    return codec.unit_quaternion(arguments['orientation'])


def level_orientation(arguments: dict[str, Any]) -> tuple[float, float, float, float]:
    """A "level" command takes no arguments."""
    codec.check_keys(arguments, ())
    return LEVEL


def joint_position(names: list[str], positions: list[float], joint: str) -> float | None:
    """The position of `joint` in a JointState's names/positions, or None when it is not there."""
    for name, position in zip(names, positions, strict=False):
        if name == joint:
            return float(position)
    return None
