"""The IMU as pure functions of time: where it truly points, and what its sensors report.

Frames follow REP 103: the world is ENU (x east, y north, z up), the body x forward, y left,
z up; a level IMU facing east has the identity orientation. Time is in seconds and comes from the
caller, so tests can step it without a clock.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np
from owl_common import quaternion as quat
from owl_common.quaternion import Quaternion, Vector

GRAVITY = 9.81                                 # m/s^2
EARTH_FIELD: Vector = (0.0, 19.5e-6, -44.5e-6)  # T in ENU: about central Europe (48 uT, 66 deg dip)
BIAS_WINDOW = 0.5                               # s of gyro samples averaged by setBias
MOTION_SOURCES = ('scripted', 'command', 'file')


class Motion(Protocol):
    """Where the IMU's true orientation comes from."""

    def orientation(self, t: float) -> Quaternion:
        """The IMU's true orientation in the world (ENU) frame at time t in s."""
        ...


class ScriptedMotion:
    """Someone holding the IMU, tilting it forward and back and turning it left and right.

    Large enough for the course's IMU projects: pitch and yaw sweep most of the kit's tilt
    (-1.3..0.9 rad) and pan (+-1.57 rad) ranges. A turtle driven at a speed proportional to pitch
    (periodic every 10 s) and a turn rate proportional to yaw (every 12 s, zero mean) has a heading
    made of multiples of 1/12 Hz, none of which cancels pitch's 1/10 Hz: its velocity has no
    constant part, so its path closes every 60 s whatever the two factors and never drifts into a
    wall. The whole motion repeats every minute.
    """

    def orientation(self, t: float) -> Quaternion:
        """The hand-held orientation at t s: roll, pitch and yaw each swing on a period of their own."""
        roll = 0.30 * math.sin(2 * math.pi * t / 15.0)
        pitch = 0.90 * math.cos(2 * math.pi * t / 10.0)
        yaw = 1.40 * math.sin(2 * math.pi * t / 12.0)
        return quat.from_euler(roll, pitch, yaw)


class CommandedMotion:
    """The true orientation turns toward the last commanded one at up to max_rate rad/s."""

    def __init__(self, max_rate: float = 3.0) -> None:
        if not (math.isfinite(max_rate) and max_rate > 0):
            raise ValueError(f'max_rate must be positive, got {max_rate}')
        self.max_rate = max_rate
        self.target: Quaternion = quat.IDENTITY
        self._current: Quaternion = quat.IDENTITY
        self._time: float | None = None

    def command(self, target: Quaternion) -> None:
        """Turn toward target from now on; ValueError for a zero or non-finite quaternion."""
        self.target = quat.normalize(target)

    def hold(self, orientation: Quaternion) -> None:
        """Be at orientation now, as the target (a restarted module: the hand has not moved)."""
        self.target = self._current = quat.normalize(orientation)

    def orientation(self, t: float) -> Quaternion:
        """The orientation at t s, turned toward the target at max_rate for the time since the last call."""
        if self._time is not None and t > self._time:
            remaining = quat.angle_between(self._current, self.target)
            reach = self.max_rate * (t - self._time)
            self._current = self.target if remaining <= reach else quat.slerp(
                self._current, self.target, reach / remaining)
        self._time = t
        return self._current


class RecordedMotion:
    """Orientation played back from a CSV file, looped; interpolated between rows.

    Each line is `t, roll, pitch, yaw` (rad) or `t, qx, qy, qz, qw`; `#` starts a comment.
    """

    def __init__(self, path: str) -> None:
        self.times: list[float] = []
        self.orientations: list[Quaternion] = []
        try:
            text = Path(path).read_text()
        except OSError as error:
            raise ValueError(f"cannot read motion file '{path}': {error.strerror}") from None
        for number, line in enumerate(text.splitlines(), 1):
            line = line.split('#', 1)[0].strip()
            if not line:
                continue
            try:
                values = [float(v) for v in line.replace(',', ' ').split()]
                if len(values) == 4:
                    orientation = quat.from_euler(*values[1:])
                elif len(values) == 5:
                    orientation = quat.normalize((values[1], values[2], values[3], values[4]))
                else:
                    raise ValueError('expected 4 or 5 numbers')
                if not all(math.isfinite(v) for v in values):
                    raise ValueError('values must be finite')
            except ValueError as error:
                raise ValueError(f"motion file '{path}' line {number}: {error}") from None
            if self.times and values[0] <= self.times[-1]:
                raise ValueError(f"motion file '{path}' line {number}: times must increase")
            self.times.append(values[0])
            self.orientations.append(orientation)
        if len(self.times) < 2:
            raise ValueError(f"motion file '{path}' needs at least two rows")

    def orientation(self, t: float) -> Quaternion:
        """The file's orientation at t s, looped over the file's time span, slerped between rows."""
        start, end = self.times[0], self.times[-1]
        t = start + (t % (end - start))
        index = max(i for i, ti in enumerate(self.times) if ti <= t)
        if index == len(self.times) - 1:
            return self.orientations[-1]
        t0, t1 = self.times[index], self.times[index + 1]
        return quat.slerp(self.orientations[index], self.orientations[index + 1], (t - t0) / (t1 - t0))


@dataclass(frozen=True)
class ImuNoise:
    """Standard deviations of the sensor errors (per sample unless said otherwise)."""

    gyro_noise: float = 0.002           # rad/s
    gyro_bias: float = 0.005            # rad/s per axis, drawn once at power-up
    accel_noise: float = 0.02           # m/s^2
    mag_noise: float = 0.2e-6           # T
    orientation_noise: float = 0.002    # rad, the fusion's jitter

    def problems(self) -> list[str]:
        """One line per standard deviation that is negative or not finite; empty when all are usable."""
        return [f'{name} must be zero or positive, got {getattr(self, name)}'
                for name in ('gyro_noise', 'gyro_bias', 'accel_noise', 'mag_noise', 'orientation_noise')
                if not (math.isfinite(getattr(self, name)) and getattr(self, name) >= 0)]


@dataclass(frozen=True)
class ImuReading:
    """One sample of the IMU: the fused orientation and what the gyro, accelerometer and magnetometer read."""

    orientation: Quaternion
    angular_velocity: Vector      # rad/s, body frame, what the gyro reports
    linear_acceleration: Vector   # m/s^2, body frame, specific force: +g on z when level
    magnetic_field: Vector        # T, body frame


def _add(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _scaled(z: list[float], sigma: float) -> Vector:
    return (z[0] * sigma, z[1] * sigma, z[2] * sigma)


class ImuSensor:
    """Turns a true orientation history into noisy sensor readings with a gyro bias."""

    def __init__(self, noise: ImuNoise | None = None, seed: int = 0) -> None:
        self.noise = noise or ImuNoise()
        problems = self.noise.problems()
        if problems:
            raise ValueError('; '.join(problems))
        self.random = np.random.default_rng(seed)
        self.bias: Vector = tuple(self.random.normal(0.0, self.noise.gyro_bias, 3).tolist())
        self.bias_correction: Vector = (0.0, 0.0, 0.0)
        self.zero: Quaternion = quat.IDENTITY
        self.true_orientation: Quaternion = quat.IDENTITY
        self._last: tuple[float, Quaternion] | None = None
        self._gyro_history: deque[tuple[float, Vector]] = deque()


    def sample(self, t: float, true_orientation: Quaternion) -> ImuReading:
        """The reading at time t; the angular velocity is the mean rate since the last sample."""
        if self._last is not None and t > self._last[0]:
            turn = quat.to_rotation_vector(quat.multiply(quat.conjugate(self._last[1]), true_orientation))
            dt = t - self._last[0]
            rate = (turn[0] / dt, turn[1] / dt, turn[2] / dt)
        else:
            rate = (0.0, 0.0, 0.0)
        self._last = (t, true_orientation)
        self.true_orientation = true_orientation
        n = self.noise
        # All twelve noise values in one draw: one numpy call costs less than three Python ones.
        z = self.random.standard_normal(12).tolist()
        gyro = _add(_add(rate, self.bias), _scaled(z[0:3], n.gyro_noise))
        self._remember(t, gyro)
        gyro = _add(gyro, _scaled(list(self.bias_correction), -1.0))
        world_to_body = quat.conjugate(true_orientation)
        accel = _add(quat.rotate(world_to_body, (0.0, 0.0, GRAVITY)), _scaled(z[3:6], n.accel_noise))
        mag = _add(quat.rotate(world_to_body, EARTH_FIELD), _scaled(z[6:9], n.mag_noise))
        jitter = quat.from_rotation_vector(_scaled(z[9:12], n.orientation_noise))
        orientation = quat.multiply(quat.multiply(quat.conjugate(self.zero), true_orientation), jitter)
        return ImuReading(orientation, gyro, accel, mag)

    def _remember(self, t: float, gyro: Vector) -> None:
        self._gyro_history.append((t, gyro))
        while self._gyro_history and self._gyro_history[0][0] < t - BIAS_WINDOW:
            self._gyro_history.popleft()

    def set_bias(self) -> tuple[bool, str]:
        """Take the mean gyro reading of the last BIAS_WINDOW s as its bias (the IMU must be still)."""
        samples = [g for _, g in self._gyro_history]
        if len(samples) < 10:
            return False, 'not enough gyro samples yet: wait half a second and retry'
        sums = [sum(s[i] for s in samples) for i in range(3)]
        mean = (sums[0] / len(samples), sums[1] / len(samples), sums[2] / len(samples))
        spread = max(math.sqrt(sum((s[i] - mean[i]) ** 2 for s in samples) / len(samples))
                     for i in range(3))
        if spread > 3 * self.noise.gyro_noise + 0.01 or max(abs(m) for m in mean) > 0.1:
            return False, 'the IMU is moving: keep it still and retry'
        self.bias_correction = mean
        return True, ('gyro bias set to ' + ', '.join(f'{m:.5f}' for m in mean) + ' rad/s')

    def set_zero_orientation(self) -> tuple[bool, str]:
        """From now on, the current true orientation reads as the identity."""
        self.zero = self.true_orientation
        return True, 'orientation zeroed: the current orientation is now the identity'
