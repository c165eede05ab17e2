"""The servo goals' pure logic: the course's sine, the bounds, the IMU's head angles."""

import math

import pytest
from geometry_msgs.msg import Quaternion
from olive_imu.euler import quaternion_to_euler
from olive_kit.description import OWL_KIT
from olive_servo.goals import PAN_BOUNDS, TILT_BOUNDS, SineGoal, bounds_problem, clamp, head_goals
from olive_sim.imu_model import ScriptedMotion


def test_the_sine_starts_at_zero_and_steps_its_input():
    sine = SineGoal(step=0.01)
    goals = [sine.next(1.0) for _ in range(4)]
    assert goals == pytest.approx([0.0, math.sin(0.01), math.sin(0.02), math.sin(0.03)])


def test_the_sine_swings_between_minus_and_plus_amplitude():
    sine = SineGoal(step=0.01)
    goals = [sine.next(1.2) for _ in range(700)]  # a little more than one period (628 goals)
    assert max(goals) == pytest.approx(1.2, abs=1e-4)
    assert min(goals) == pytest.approx(-1.2, abs=1e-4)


def test_the_sine_input_stays_bounded_for_hours():
    sine = SineGoal(step=0.01)
    for _ in range(100_000):
        sine.next(1.0)
    assert 0.0 <= sine.phase < 2 * math.pi
    assert sine.next(1.0) == pytest.approx(math.sin(100_000 * 0.01), abs=1e-9)


def test_clamp():
    assert clamp(2.0, -1.3, 0.9) == 0.9
    assert clamp(-2.0, -1.3, 0.9) == -1.3
    assert clamp(0.5, -1.3, 0.9) == 0.5


def test_bounds_must_be_ordered():
    assert bounds_problem('pan', -1.0, 1.0) is None
    assert bounds_problem('tilt', 0.5, 0.5) == 'tilt_min (0.5) must be less than tilt_max (0.5)'
    assert bounds_problem('pan', 1.0, -1.0) == 'pan_min (1.0) must be less than pan_max (-1.0)'


def test_the_head_follows_the_imu_with_the_same_signs():
    # IMU turned left (positive yaw) -> pan left (positive); nose down (positive pitch) -> look down.
    assert head_goals(0.4, 0.7, PAN_BOUNDS, TILT_BOUNDS) == pytest.approx((0.7, 0.4))
    assert head_goals(-0.4, -0.7, PAN_BOUNDS, TILT_BOUNDS) == pytest.approx((-0.7, -0.4))


@pytest.mark.parametrize(('pitch', 'yaw'), [(1.5, 3.0), (-1.5, -3.0), (0.95, -1.6), (-1.31, 1.58)])
def test_head_goals_never_leave_the_bounds(pitch, yaw):
    pan, tilt = head_goals(pitch, yaw, PAN_BOUNDS, TILT_BOUNDS)
    assert PAN_BOUNDS[0] <= pan <= PAN_BOUNDS[1]
    assert TILT_BOUNDS[0] <= tilt <= TILT_BOUNDS[1]
    assert pan in PAN_BOUNDS
    assert tilt in TILT_BOUNDS


def test_the_bounds_are_the_kits():
    """The defaults are the simulated kit's servo ranges (olive_sim's owl_kit launch)."""
    ranges = {m.namespace: (m.parameters['min_position'], m.parameters['max_position'])
              for m in OWL_KIT if m.module_type == 'servo'}
    assert ranges == {'pan': PAN_BOUNDS, 'tilt': TILT_BOUNDS}


def test_the_simulated_imu_sweeps_most_of_both_ranges():
    """Item 4 of issue 11: olive_sim's scripted IMU moves the head through most of its range."""
    motion = ScriptedMotion()
    pans, tilts = [], []
    for k in range(600):  # a minute, every 0.1 s
        x, y, z, w = motion.orientation(k / 10)
        _roll, pitch, yaw = quaternion_to_euler(Quaternion(x=x, y=y, z=z, w=w))
        pan, tilt = head_goals(pitch, yaw, PAN_BOUNDS, TILT_BOUNDS)
        pans.append(pan)
        tilts.append(tilt)
    assert (max(pans) - min(pans)) / (PAN_BOUNDS[1] - PAN_BOUNDS[0]) > 0.85
    assert (max(tilts) - min(tilts)) / (TILT_BOUNDS[1] - TILT_BOUNDS[0]) > 0.8
