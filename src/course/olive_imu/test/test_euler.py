"""The course's quaternion -> Euler equations and the checks on IMU orientations."""

import math

import pytest
from geometry_msgs.msg import Quaternion
from olive_imu.euler import orientation_problem, quaternion_to_euler
from sensor_msgs.msg import Imu


def from_euler(roll, pitch, yaw):
    """Rotation yaw about z, then pitch about the new y, then roll about the new x (ROS RPY)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return Quaternion(x=sr * cp * cy - cr * sp * sy, y=cr * sp * cy + sr * cp * sy,
                      z=cr * cp * sy - sr * sp * cy, w=cr * cp * cy + sr * sp * sy)


def test_identity_is_level_and_facing_ahead():
    assert quaternion_to_euler(Quaternion()) == (0.0, 0.0, 0.0)


@pytest.mark.parametrize('angles', [(0.3, 0.0, 0.0), (0.0, 0.4, 0.0), (0.0, 0.0, -1.2),
                                    (0.2, -0.7, 2.5), (-3.0, 1.2, -3.1)])
def test_round_trip(angles):
    assert quaternion_to_euler(from_euler(*angles)) == pytest.approx(angles)


def test_single_axis_rotations_have_the_right_sign():
    half = math.sqrt(0.5)
    # 90 deg about +y: the IMU's nose (x) points down, pitch +pi/2; about +z: turned left, yaw +pi/2.
    assert quaternion_to_euler(Quaternion(x=0.0, y=half, z=0.0, w=half))[1] == pytest.approx(math.pi / 2)
    assert quaternion_to_euler(Quaternion(x=0.0, y=0.0, z=half, w=half))[2] == pytest.approx(math.pi / 2)
    assert quaternion_to_euler(Quaternion(x=half, y=0.0, z=0.0, w=half))[0] == pytest.approx(math.pi / 2)


def test_a_scaled_quaternion_gives_the_same_angles():
    q = from_euler(0.1, 0.5, -0.8)
    scaled = Quaternion(x=3 * q.x, y=3 * q.y, z=3 * q.z, w=3 * q.w)
    assert quaternion_to_euler(scaled) == pytest.approx((0.1, 0.5, -0.8))


def test_pitch_at_the_pole_does_not_fail_on_rounding():
    half = math.sqrt(0.5) * (1 + 1e-12)  # 2 (w y - z x) is a hair above 1
    assert quaternion_to_euler(Quaternion(x=0.0, y=half, z=0.0, w=half))[1] == pytest.approx(math.pi / 2)


def test_usable_orientations_have_no_problem():
    assert orientation_problem(Quaternion()) is None
    assert orientation_problem(from_euler(0.1, 0.2, 0.3), [0.01] * 9) is None
    msg = Imu()  # its covariance is a numpy array
    assert orientation_problem(msg.orientation, msg.orientation_covariance) is None
    msg.orientation_covariance[0] = -1.0
    assert 'no orientation' in orientation_problem(msg.orientation, msg.orientation_covariance)


@pytest.mark.parametrize(('q', 'covariance', 'problem'), [
    (Quaternion(x=math.nan), [0.0] * 9, 'not finite'),
    (Quaternion(w=math.inf), [0.0] * 9, 'not finite'),
    (Quaternion(w=0.0), [0.0] * 9, 'zero, not a rotation'),
    (Quaternion(x=1e-9, w=0.0), [0.0] * 9, 'zero, not a rotation'),
    (Quaternion(), [-1.0] + [0.0] * 8, 'no orientation'),
])
def test_unusable_orientations_say_why(q, covariance, problem):
    assert problem in orientation_problem(q, covariance)
