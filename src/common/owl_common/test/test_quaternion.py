"""The one quaternion module: Euler angles by the course's formulas, and what is not a rotation."""

import math

import pytest
from owl_common import quaternion as quat


def test_euler_angles_survive_a_round_trip():
    roll, pitch, yaw = 0.3, -0.4, 1.2
    assert quat.to_euler(quat.from_euler(roll, pitch, yaw)) == pytest.approx((roll, pitch, yaw))


def test_usable_euler_scales_a_quaternion_to_unit_length_first():
    doubled = tuple(2 * c for c in quat.from_euler(0.0, 0.5, 0.0))
    assert quat.usable_euler(doubled) == pytest.approx((0.0, 0.5, 0.0))


@pytest.mark.parametrize('q', [(0.0, 0.0, 0.0, 0.0), (math.nan, 0.0, 0.0, 1.0), (0.0, math.inf, 0.0, 1.0)])
def test_usable_euler_has_no_angles_for_what_is_not_a_rotation(q):
    assert quat.usable_euler(q) is None
