"""Section 4.4 project "Control Olive Servos with IMU": the pan and tilt servos point where the IMU points."""

import signal
import sys
import time

import rclpy
from geometry_msgs.msg import Quaternion
from olive_imu.euler import orientation_problem, quaternion_to_euler
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.exceptions import InvalidTopicNameException, ParameterException
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from rclpy.timer import Timer
from sensor_msgs.msg import Imu
from std_msgs.msg import Float32

from olive_servo.bound_parameters import BoundParameters
from olive_servo.goals import head_goals
from olive_servo.torque import ServoTorque, TorqueError

DEFAULT_IMU_TOPIC = '/olive/imu/x1684267976913/imu'  # the course's IMU, also olive_sim's
SERVOS = ('pan', 'tilt')
PUBLISH_PERIOD = 0.01  # s, as the course's keyboard_servos
STALE_AFTER = 0.5      # s without a usable IMU message: stop sending goals (the servos hold)
WARN_EVERY = 2.0       # s between two warnings about bad IMU messages
WAITING_EVERY = 5.0    # s between two "waiting for" lines


class ImuControlRobot(Node):

    def __init__(self) -> None:
        super().__init__('imu_control_robot')
        self.declare_parameter('imu_topic', DEFAULT_IMU_TOPIC, ParameterDescriptor(
            description='sensor_msgs/msg/Imu topic of the IMU.', read_only=True))
        self.bounds = BoundParameters(self, SERVOS)  # pan_min .. tilt_max, each pair checked
        self.imu_topic = self.get_parameter('imu_topic').value
        self.orientation = Quaternion()
        self.last_imu_time: float | None = None  # time.monotonic() of the last usable IMU message
        self.steering = False
        self.torque = ServoTorque(self, SERVOS)
        self.publishers_ = {servo: self.create_publisher(Float32, f'/olive/servo/{servo}/goal/position', 10)
                            for servo in SERVOS}
        # Best effort matches an IMU publishing either best effort or reliable (QoS: section 4.5).
        try:
            self.subscription = self.create_subscription(
                Imu, self.imu_topic, self.imu_callback, qos_profile_sensor_data)
        except InvalidTopicNameException:
            raise ValueError(f"imu_topic '{self.imu_topic}' is not a valid topic name") from None
        self.timer: Timer | None = None  # created once the torque is on: the servos ignore goals before

    def enable_torque(self) -> None:
        self.torque.enable()
        self.timer = self.create_timer(PUBLISH_PERIOD, self.publish_goals)

    def disable_torque(self) -> None:
        if self.timer is not None:
            self.timer.cancel()  # no goal may follow the torque requests
        self.torque.disable()

    def imu_callback(self, msg: Imu) -> None:
        problem = orientation_problem(msg.orientation, msg.orientation_covariance)
        if problem:
            self.get_logger().warning(f'IMU message ignored: {problem}', throttle_duration_sec=WARN_EVERY)
            return
        self.orientation = msg.orientation
        self.last_imu_time = time.monotonic()

    def publish_goals(self) -> None:
        if self.last_imu_time is None or time.monotonic() - self.last_imu_time > STALE_AFTER:
            self.wait_for_imu()
            return
        if not self.steering:
            self.steering = True
            self.get_logger().info(f'IMU data on {self.imu_topic}: steering the pan and tilt servos')
        _roll, pitch, yaw = quaternion_to_euler(self.orientation)
        pan, tilt = head_goals(pitch, yaw, self.bounds.bounds('pan'), self.bounds.bounds('tilt'))
        for servo, goal in (('pan', pan), ('tilt', tilt)):
            msg = Float32()
            msg.data = goal
            self.publishers_[servo].publish(msg)

    def wait_for_imu(self) -> None:
        if self.steering:
            self.steering = False
            self.get_logger().warning(
                f'no usable IMU message on {self.imu_topic} for {STALE_AFTER} s: the servos hold')
        self.get_logger().info(
            f'waiting for IMU messages on {self.imu_topic} '
            f'({self.count_publishers(self.imu_topic)} publisher(s) so far)',
            throttle_duration_sec=WAITING_EVERY)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    imu_control_robot = None
    try:
        imu_control_robot = ImuControlRobot()
        imu_control_robot.enable_torque()
        rclpy.spin(imu_control_robot)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except TorqueError as error:
        assert imu_control_robot is not None  # only enable_torque() raises it
        imu_control_robot.get_logger().error(str(error))
        sys.exit(1)
    except (ParameterException, ValueError) as error:
        if imu_control_robot is not None:
            raise
        print(f'imu_control_robot: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if imu_control_robot is not None:
            imu_control_robot.disable_torque()
            imu_control_robot.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
