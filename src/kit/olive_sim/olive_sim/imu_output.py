"""The imu and magnetometer topics of a module (the IMU module and the camera both have them)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from owl_common.periodic import scheduled_time
from owl_common.quaternion import Quaternion
from rcl_interfaces.msg import FloatingPointRange, IntegerRange
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.serialization import serialize_message
from sensor_msgs.msg import Imu, MagneticField

from olive_sim.imu_model import ImuNoise, ImuSensor
from olive_sim.module_node import SENSOR_CATCH_UP, OliveModule, describe
from olive_sim.serialized import STAMP_MARKER, SerializedTemplate, markers

NOISE_DESCRIPTIONS = {
    'gyro_noise': 'Gyro white noise, standard deviation per sample [rad/s].',
    'gyro_bias': 'Standard deviation of the constant gyro bias drawn at start [rad/s].',
    'accel_noise': 'Accelerometer noise, standard deviation per sample [m/s^2].',
    'mag_noise': 'Magnetometer noise, standard deviation per sample [T].',
    'orientation_noise': 'Jitter of the fused orientation, standard deviation [rad].',
}
RELIABILITIES = {'reliable': ReliabilityPolicy.RELIABLE, 'best_effort': ReliabilityPolicy.BEST_EFFORT}


def reliability(name: str, parameter: str) -> ReliabilityPolicy:
    """The policy named 'reliable' or 'best_effort'; ValueError naming the parameter for any other name."""
    if name not in RELIABILITIES:
        raise ValueError(f"{parameter} must be one of {', '.join(RELIABILITIES)}, got '{name}'")
    return RELIABILITIES[name]


class ImuOutput:
    """Declares the IMU parameters on `node`, owns the sensor model and publishes its readings."""

    def __init__(self, node: OliveModule, topic: Callable[[str], str], frame_id: str,
                 true_orientation: Callable[[float], Quaternion]) -> None:
        self.node = node
        self.true_orientation = true_orientation
        defaults = ImuNoise()
        for name, description in NOISE_DESCRIPTIONS.items():
            node.declare_parameter(name, getattr(defaults, name), describe(
                description, True, floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0)]))
        node.declare_parameter('seed', 0, describe(
            'Seed of the sensor noise and bias (same seed, same errors).', True,
            integer_range=[IntegerRange(from_value=0, to_value=2**31 - 1, step=1)]))
        node.declare_parameter('imu_rate', 100.0, describe(
            'Publication rate of imu and magnetometer [Hz].', True,
            floating_point_range=[FloatingPointRange(from_value=1.0, to_value=1000.0)]))
        node.declare_parameter('imu_frame_id', frame_id, describe(
            'header.frame_id of imu and magnetometer.', True))
        node.declare_parameter('imu_reliability', 'reliable', describe(
            'Reliability of the imu publisher: reliable or best_effort.', True))
        value = node.get_parameter
        self.noise = ImuNoise(**{name: value(name).value for name in NOISE_DESCRIPTIONS})
        self.sensor = ImuSensor(self.noise, value('seed').value)
        self.frame_id = value('imu_frame_id').value
        qos = QoSProfile(depth=10, reliability=reliability(value('imu_reliability').value, 'imu_reliability'))
        self.imu_publisher = node.create_publisher(Imu, topic('imu'), qos)
        self.mag_publisher = node.create_publisher(MagneticField, topic('magnetometer'), qos)
        self.lock = threading.Lock()  # the sensor is sampled on the output thread, reset by services
        self._imu, self._mag = self._templates()
        # The motion goes on where the process before a restart left it (restart.py).
        self._epoch = time.monotonic() - float(node.handover.get('imu_time', 0.0))
        self.latest: Quaternion | None = None  # the last orientation published, for the web page
        self.traffic = node.traffic.counter()
        self.thread = node.create_periodic(value('imu_rate').value, self.publish, 'imu',
                                           catch_up=SENSOR_CATCH_UP)

    def _templates(self) -> tuple[SerializedTemplate, SerializedTemplate]:
        """Serialized imu and magnetometer messages to fill with each reading.

        The imu's fields are the orientation, angular velocity and linear acceleration (10 values), the
        magnetometer's the magnetic field (3 values).
        """
        sec, nanosec = STAMP_MARKER
        values = markers(10)
        imu = Imu()
        imu.header.stamp.sec, imu.header.stamp.nanosec = sec, nanosec
        imu.header.frame_id = self.frame_id
        o, av, la = imu.orientation, imu.angular_velocity, imu.linear_acceleration
        o.x, o.y, o.z, o.w, av.x, av.y, av.z, la.x, la.y, la.z = values
        imu.orientation_covariance = _diagonal(self.noise.orientation_noise ** 2)
        imu.angular_velocity_covariance = _diagonal(self.noise.gyro_noise ** 2)
        imu.linear_acceleration_covariance = _diagonal(self.noise.accel_noise ** 2)
        mag = MagneticField()
        mag.header.stamp.sec, mag.header.stamp.nanosec = sec, nanosec
        mag.header.frame_id = self.frame_id
        mf = mag.magnetic_field
        mf.x, mf.y, mf.z = values[:3]
        mag.magnetic_field_covariance = _diagonal(self.noise.mag_noise ** 2)
        return (SerializedTemplate(serialize_message(imu), values),
                SerializedTemplate(serialize_message(mag), values[:3]))

    def publish(self) -> None:
        """Sample the sensor at its due time and publish the imu and magnetometer messages (IMU thread)."""
        # Sampled and stamped on the rate's schedule, however late the thread runs: the stamps of
        # a real IMU are its own clock's, so their spacing stays 1/imu_rate under any load.
        due = scheduled_time()
        stamp = self.node.ros_time_at(due)
        t = due - self._epoch
        with self.lock:
            reading = self.sensor.sample(t, self.true_orientation(t))
        imu = self._imu.fill(stamp, (*reading.orientation, *reading.angular_velocity,
                                     *reading.linear_acceleration))
        mag = self._mag.fill(stamp, reading.magnetic_field)
        self.imu_publisher.publish(imu)
        self.mag_publisher.publish(mag)
        self.latest = reading.orientation
        self.traffic.sent += len(imu) + len(mag)

    def motion_time(self) -> float:
        """S of motion so far (a restarted module goes on from there)."""
        return time.monotonic() - self._epoch


def _diagonal(variance: float) -> list[float]:
    # Zero means "unknown" in sensor_msgs/Imu, so a noiseless axis reports a tiny variance instead.
    v = max(variance, 1e-12)
    return [v, 0.0, 0.0, 0.0, v, 0.0, 0.0, 0.0, v]
