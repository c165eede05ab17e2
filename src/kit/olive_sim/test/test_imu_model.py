"""Quaternion helpers, motion sources and the IMU sensor model, stepped without a clock."""

import math

import pytest
from olive_sim.imu_model import (
    GRAVITY,
    CommandedMotion,
    ImuNoise,
    ImuSensor,
    RecordedMotion,
    ScriptedMotion,
)
from owl_common import quaternion as quat

RATE = 100.0


def norm(v):
    return math.sqrt(sum(c * c for c in v))


def test_euler_round_trip_and_course_formulas():
    q = quat.from_euler(0.2, -0.3, 1.1)
    assert quat.to_euler(q) == pytest.approx((0.2, -0.3, 1.1))
    assert quat.rotate(quat.from_euler(0, 0, math.pi / 2), (1, 0, 0)) == pytest.approx((0, 1, 0), abs=1e-12)


def test_rotation_vector_round_trip_and_slerp():
    r = (0.1, -0.4, 0.25)
    assert quat.to_rotation_vector(quat.from_rotation_vector(r)) == pytest.approx(r)
    a, b = quat.IDENTITY, quat.from_euler(0, 0, 1.0)
    assert quat.to_euler(quat.slerp(a, b, 0.25))[2] == pytest.approx(0.25)
    with pytest.raises(ValueError, match='no usable length'):
        quat.normalize((0.0, 0.0, 0.0, 0.0))


def test_at_rest_the_accelerometer_reads_gravity():
    sensor = ImuSensor(seed=1)
    norms = [norm(sensor.sample(k / RATE, quat.IDENTITY).linear_acceleration) for k in range(200)]
    assert sum(norms) / len(norms) == pytest.approx(GRAVITY, abs=0.01)


def test_integrated_gyro_matches_the_orientation_change():
    sensor, motion = ImuSensor(seed=2), ScriptedMotion()
    readings = [sensor.sample(k / RATE, motion.orientation(k / RATE)) for k in range(101)]
    integrated = readings[0].orientation
    for reading in readings[1:]:
        integrated = quat.multiply(integrated, quat.from_rotation_vector(
            tuple(w / RATE for w in reading.angular_velocity)))
    turned = quat.angle_between(readings[0].orientation, readings[-1].orientation)
    assert turned > 0.1  # the scripted hand really moves
    assert quat.angle_between(integrated, readings[-1].orientation) < 0.03


def test_scripted_motion_sweeps_the_kit_ranges_and_repeats_every_minute():
    motion = ScriptedMotion()
    angles = [quat.to_euler(motion.orientation(k / 10)) for k in range(600)]
    pitches, yaws = [a[1] for a in angles], [a[2] for a in angles]
    assert min(pitches) < -0.85
    assert max(pitches) > 0.85  # of the tilt servo's -1.3..0.9 rad
    assert min(yaws) < -1.35
    assert max(yaws) > 1.35     # of the pan servo's +-1.57 rad
    for t in (0.0, 3.3, 17.0):
        assert quat.angle_between(motion.orientation(t), motion.orientation(t + 60.0)) < 1e-9


@pytest.mark.parametrize(('speed', 'turn'), [(1.0, 1.0), (1.5, 1.5), (3.0, 0.4), (0.5, 2.5)])
@pytest.mark.parametrize('start', [0.0, 7.0, 41.0])
def test_a_turtle_driven_by_pitch_and_yaw_comes_back_after_a_minute(speed, turn, start):
    """The scripted motion's promise to the course's imu_turtle: a closed path, however it is driven.

    Speed = f * pitch and turn rate = g * yaw give a closed path for any f and g, from any moment the
    turtle starts.
    """
    motion, dt = ScriptedMotion(), 0.005
    x = y = heading = 0.0
    farthest = 0.0
    for k in range(round(60.0 / dt)):
        _, pitch, yaw = quat.to_euler(motion.orientation(start + (k + 0.5) * dt))
        heading += turn * yaw * dt
        x += speed * pitch * math.cos(heading) * dt
        y += speed * pitch * math.sin(heading) * dt
        farthest = max(farthest, math.hypot(x, y))
    assert farthest > 1.0 * speed  # it really drives around
    assert math.hypot(x, y) < 0.01 * farthest


def test_magnetometer_heading_follows_yaw():
    sensor = ImuSensor(ImuNoise(mag_noise=0.0))
    headings = []
    for yaw in (0.0, 0.5, 1.0):
        m = sensor.sample(0.0, quat.from_euler(0, 0, yaw)).magnetic_field
        headings.append(math.atan2(m[0], m[1]))  # angle of magnetic north from the body's +y
    assert headings[1] - headings[0] == pytest.approx(0.5, abs=1e-9)
    assert headings[2] - headings[0] == pytest.approx(1.0, abs=1e-9)


def test_zero_orientation_makes_the_current_one_identity():
    sensor = ImuSensor(ImuNoise(orientation_noise=0.0))
    tilted = quat.from_euler(0.3, 0.2, -0.7)
    sensor.sample(0.0, tilted)
    assert sensor.set_zero_orientation()[0]
    assert sensor.sample(0.01, tilted).orientation == pytest.approx(quat.IDENTITY, abs=1e-12)


def test_set_bias_removes_the_gyro_bias_at_rest_and_refuses_when_moving():
    sensor = ImuSensor(ImuNoise(gyro_bias=0.02), seed=3)
    assert not sensor.set_bias()[0]  # no samples yet
    for k in range(60):
        sensor.sample(k / RATE, quat.IDENTITY)
    before = sensor.sample(0.6, quat.IDENTITY).angular_velocity
    ok, message = sensor.set_bias()
    assert ok, message
    after = [sensor.sample(0.6 + k / RATE, quat.IDENTITY).angular_velocity for k in range(1, 101)]
    mean = [sum(a[i] for a in after) / len(after) for i in range(3)]
    assert max(abs(b) for b in before) > 0.005
    assert max(abs(m) for m in mean) < 0.001
    moving = ImuSensor(seed=4)
    for k in range(60):
        moving.sample(k / RATE, quat.from_euler(0, 0, 2.0 * k / RATE))
    assert moving.set_bias() == (False, 'the IMU is moving: keep it still and retry')


def test_seeded_noise_is_reproducible():
    a = [ImuSensor(seed=7).sample(0.0, quat.IDENTITY) for _ in range(2)]
    assert a[0] == a[1]
    assert ImuSensor(seed=8).sample(0.0, quat.IDENTITY) != a[0]


def test_commanded_motion_turns_at_its_rate_limit():
    motion = CommandedMotion(max_rate=1.0)
    motion.orientation(0.0)
    motion.command(quat.from_euler(0, 0, 1.5))
    assert quat.to_euler(motion.orientation(0.5))[2] == pytest.approx(0.5)
    assert quat.to_euler(motion.orientation(3.0))[2] == pytest.approx(1.5)
    with pytest.raises(ValueError, match='not a rotation'):
        motion.command((math.nan, 0.0, 0.0, 1.0))


def test_recorded_motion_plays_a_file_in_a_loop(tmp_path):
    path = tmp_path / 'motion.csv'
    path.write_text('# t, roll, pitch, yaw\n0, 0, 0, 0\n1, 0, 0, 1.0\n2, 0, 0, 0\n')
    motion = RecordedMotion(str(path))
    assert quat.to_euler(motion.orientation(0.5))[2] == pytest.approx(0.5)
    assert quat.to_euler(motion.orientation(2.5))[2] == pytest.approx(0.5)


@pytest.mark.parametrize(('text', 'message'), [
    ('0, 0, 0, 0\n', 'at least two rows'),
    ('0, 0, 0\n1, 0, 0, 1\n', 'line 1: expected 4 or 5 numbers'),
    ('0, a, 0, 0\n1, 0, 0, 1\n', 'line 1'),
    ('0, 0, 0, 0\n0, 0, 0, 1\n', 'line 2: times must increase'),
    ('0, 0, 0, 0, 0\n1, 0, 0, 0, 1\n', 'line 1: not a rotation'),
    ('0, nan, 0, 0\n1, 0, 0, 1\n', 'line 1: values must be finite'),
])
def test_bad_motion_files_are_refused_with_the_line(tmp_path, text, message):
    path = tmp_path / 'bad.csv'
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        RecordedMotion(str(path))


def test_missing_motion_file_and_bad_noise():
    with pytest.raises(ValueError, match='cannot read motion file'):
        RecordedMotion('/nonexistent/motion.csv')
    with pytest.raises(ValueError, match='gyro_noise must be zero or positive'):
        ImuSensor(ImuNoise(gyro_noise=-1.0))
