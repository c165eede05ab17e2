"""Section 4.4 project "Control Servo": move the pan servo in a sine, torque on first, off at Ctrl-C."""

import signal
import sys

import rclpy
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import ParameterException
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.timer import Timer
from std_msgs.msg import Float32

from olive_servo.goals import PAN_BOUNDS, SineGoal
from olive_servo.torque import ServoTorque, TorqueError

SERVO = 'pan'
GOAL_TOPIC = f'/olive/servo/{SERVO}/goal/position'
STEP = 0.01  # rad the sine's input grows by per goal: at 100 goals/s one period takes 6.3 s


class ControlServo(Node):

    def __init__(self) -> None:
        super().__init__('control_servo')
        self.declare_parameter('frequency', 100.0, ParameterDescriptor(
            description='Goals published per second (the course starts with one every 0.01 s); '
                        'the sine speeds up with it.',
            floating_point_range=[FloatingPointRange(from_value=1.0, to_value=500.0)]))
        self.declare_parameter('amplitude', 1.0, ParameterDescriptor(
            description='Largest goal in rad: the sine swings between -amplitude and +amplitude.',
            floating_point_range=[FloatingPointRange(from_value=0.0, to_value=PAN_BOUNDS[1])]))
        self.torque = ServoTorque(self, [SERVO])
        self.publisher_ = self.create_publisher(Float32, GOAL_TOPIC, 10)
        self.sine = SineGoal(STEP)
        self.timer: Timer | None = None  # created once the torque is on: the servo ignores goals before
        self.add_post_set_parameters_callback(self.parameters_changed)

    def period(self) -> float:
        return 1.0 / self.get_parameter('frequency').value

    def enable_torque(self) -> None:
        self.torque.enable()
        self.timer = self.create_timer(self.period(), self.publish_goal)

    def disable_torque(self) -> None:
        if self.timer is not None:
            self.timer.cancel()  # no goal may follow the torque request
        self.torque.disable()

    def publish_goal(self) -> None:
        msg = Float32()
        msg.data = self.sine.next(self.get_parameter('amplitude').value)
        self.publisher_.publish(msg)

    def parameters_changed(self, parameters: list[Parameter]) -> None:
        if self.timer is not None and any(p.name == 'frequency' for p in parameters):
            self.timer.timer_period_ns = round(self.period() * 1e9)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    control_servo = None
    try:
        control_servo = ControlServo()
        control_servo.enable_torque()
        rclpy.spin(control_servo)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except TorqueError as error:
        assert control_servo is not None  # only enable_torque() raises it
        control_servo.get_logger().error(str(error))
        sys.exit(1)
    except (ParameterException, ValueError) as error:
        if control_servo is not None:
            raise
        print(f'control_servo: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if control_servo is not None:
            control_servo.disable_torque()
            control_servo.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
