"""Section 4.3.2: the Olive IMU drives the turtlesim turtle (pitch -> speed, yaw -> turn rate)."""

import signal
import sys
import time

import rclpy
from geometry_msgs.msg import Quaternion, Twist
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import InvalidTopicNameException, ParameterException
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import Imu

from olive_imu.drive import turtle_velocity
from olive_imu.euler import orientation_problem, quaternion_to_euler

DEFAULT_IMU_TOPIC = '/olive/imu/x1684267976913/imu'  # the course's IMU, also olive_sim's
# The course writes /turtle/cmd_vel; turtlesim's first turtle is turtle1.
CMD_VEL_TOPIC = '/turtle1/cmd_vel'
PUBLISH_PERIOD = 0.05  # s
STALE_AFTER = 0.5      # s without a usable IMU message: stop driving (turtlesim halts 1 s later)
WARN_EVERY = 2.0       # s between two warnings about bad IMU messages
WAITING_EVERY = 5.0    # s between two "waiting for" lines


def factor_descriptor(description: str) -> ParameterDescriptor:
    return ParameterDescriptor(
        description=description,
        floating_point_range=[FloatingPointRange(from_value=0.0, to_value=10.0)])


class ImuTurtle(Node):

    def __init__(self) -> None:
        super().__init__('imu_turtle')
        self.declare_parameter('imu_topic', DEFAULT_IMU_TOPIC, ParameterDescriptor(
            description='sensor_msgs/msg/Imu topic of the IMU.', read_only=True))
        self.declare_parameter('speed_factor', 1.5, factor_descriptor(
            'Forward speed per radian of pitch (tilting the IMU forward), m/s per rad.'))
        self.declare_parameter('turn_factor', 1.5, factor_descriptor(
            'Turn rate per radian of yaw (turning the IMU left), rad/s per rad.'))
        self.imu_topic = self.get_parameter('imu_topic').value
        self.orientation = Quaternion()
        self.last_imu_time: float | None = None  # time.monotonic() of the last usable IMU message
        self.driving = False
        # Best effort matches an IMU publishing either best effort or reliable (QoS: section 4.5).
        try:
            self.subscription = self.create_subscription(
                Imu, self.imu_topic, self.imu_callback, qos_profile_sensor_data)
        except InvalidTopicNameException:
            raise ValueError(f"imu_topic '{self.imu_topic}' is not a valid topic name") from None
        self.publisher_ = self.create_publisher(Twist, CMD_VEL_TOPIC, 10)
        self.timer = self.create_timer(PUBLISH_PERIOD, self.publish_velocity)

    def imu_callback(self, msg: Imu) -> None:
        problem = orientation_problem(msg.orientation, msg.orientation_covariance)
        if problem:
            self.get_logger().warning(f'IMU message ignored: {problem}', throttle_duration_sec=WARN_EVERY)
            return
        self.orientation = msg.orientation
        self.last_imu_time = time.monotonic()

    def publish_velocity(self) -> None:
        if self.last_imu_time is None or time.monotonic() - self.last_imu_time > STALE_AFTER:
            self.wait_for_imu()
            return
        if not self.driving:
            self.driving = True
            self.get_logger().info(f'IMU data on {self.imu_topic}: driving {CMD_VEL_TOPIC}')
        _roll, pitch, yaw = quaternion_to_euler(self.orientation)
        msg = Twist()
        msg.linear.x, msg.angular.z = turtle_velocity(
            pitch, yaw, self.get_parameter('speed_factor').value, self.get_parameter('turn_factor').value)
        self.publisher_.publish(msg)

    def wait_for_imu(self) -> None:
        if self.driving:
            self.driving = False
            self.get_logger().warning(
                f'no usable IMU message on {self.imu_topic} for {STALE_AFTER} s: the turtle stops')
        self.get_logger().info(
            f'waiting for IMU messages on {self.imu_topic} '
            f'({self.count_publishers(self.imu_topic)} publisher(s) so far)',
            throttle_duration_sec=WAITING_EVERY)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    imu_turtle = None
    try:
        imu_turtle = ImuTurtle()
        rclpy.spin(imu_turtle)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except (ParameterException, ValueError) as error:
        if imu_turtle is not None:
            raise
        print(f'imu_turtle: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # ros2 launch passes on a second Ctrl-C
        if imu_turtle is not None:
            imu_turtle.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
