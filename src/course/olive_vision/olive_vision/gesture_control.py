"""Section 4.7 project "Use Gesture Control": the head answers the gestures the camera recognises.

The camera's gesture app publishes the last gesture it recognised on tpu/gesture. Both hands up:
the head nods; hands on hip: it shakes; one hand up or out: it looks that way and back. With
target:=turtle the gestures drive turtlesim's turtle instead (the project's extra).
"""

import signal
import sys
import time

import rclpy
from geometry_msgs.msg import Twist
from olive_servo.torque import ServoTorque, TorqueError
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.exceptions import InvalidTopicNameException, ParameterException
from rclpy.node import Node
from rclpy.timer import Timer
from std_msgs.msg import Float32, String

from olive_vision.gestures import GESTURES, MOTIONS, NO_GESTURE, MotionPlayer, words

DEFAULT_GESTURE_TOPIC = '/olive/camera/eye/tpu/gesture'  # the camera's gesture app, also olive_sim's
SERVOS = ('pan', 'tilt')
TARGETS = ('head', 'turtle')
PERIOD = 0.05  # s between two goals (or turtle commands)
# The turtle's velocity for each gesture: (linear x m/s, angular z rad/s).
TURTLE = {'1': (0.0, 0.0), '2': (1.5, 0.0), '3': (1.0, 1.5), '4': (1.0, -1.5),
          '5': (0.0, 1.5), '6': (0.0, -1.5), '7': (0.0, 0.0)}


class GestureControl(Node):

    def __init__(self) -> None:
        super().__init__('gesture_control')
        self.declare_parameter('gesture_topic', DEFAULT_GESTURE_TOPIC, ParameterDescriptor(
            description="std_msgs/msg/String topic of the camera's gesture app.", read_only=True))
        self.declare_parameter('target', 'head', ParameterDescriptor(
            description="What the gestures move: 'head' (the pan/tilt servos) or 'turtle' (turtlesim).",
            read_only=True))
        self.gesture_topic = self.get_parameter('gesture_topic').value
        self.target = self.get_parameter('target').value
        if self.target not in TARGETS:
            raise ValueError(f"target '{self.target}' is not one of {', '.join(TARGETS)}")
        self.gesture = NO_GESTURE
        self.motion: MotionPlayer | None = None
        if self.target == 'head':
            self.torque = ServoTorque(self, SERVOS)
            self.publishers_ = {
                servo: self.create_publisher(Float32, f'/olive/servo/{servo}/goal/position', 10)
                for servo in SERVOS}
        else:
            self.cmd_vel_publisher = self.create_publisher(Twist, '/turtle1/cmd_vel', 10)
        try:
            self.subscription = self.create_subscription(
                String, self.gesture_topic, self.gesture_callback, 10)
        except InvalidTopicNameException:
            raise ValueError(f"gesture_topic '{self.gesture_topic}' is not a valid topic name") from None
        self.timer: Timer | None = None  # created once the torque is on: the servos ignore goals before

    def start(self) -> None:
        if self.target == 'head':
            self.torque.enable()
        self.timer = self.create_timer(PERIOD, self.move)
        self.get_logger().info(f'waiting for gestures on {self.gesture_topic}')

    def stop(self) -> None:
        if self.timer is not None:
            self.timer.cancel()  # no goal may follow the torque requests
        if self.target == 'head':
            self.torque.disable()
        else:
            self.cmd_vel_publisher.publish(Twist())  # the turtle stops

    def gesture_callback(self, msg: String) -> None:
        if msg.data == self.gesture:
            return  # the app repeats its last gesture with every image
        self.gesture = msg.data
        if msg.data not in GESTURES:
            if msg.data != NO_GESTURE:
                self.get_logger().warning(f"unknown gesture label '{msg.data}': ignored")
            return
        if self.target == 'head':
            self.motion = MotionPlayer(MOTIONS[GESTURES[msg.data][1]], time.monotonic())
            self.get_logger().info(f'gesture {msg.data} ({words(msg.data)}): {GESTURES[msg.data][1]}')
        else:
            self.get_logger().info(f'gesture {msg.data} ({words(msg.data)}): turtle {TURTLE[msg.data]}')

    def move(self) -> None:
        if self.target == 'turtle':
            if self.gesture in TURTLE:
                twist = Twist()
                twist.linear.x, twist.angular.z = TURTLE[self.gesture]
                self.cmd_vel_publisher.publish(twist)
            return
        goal = self.motion.goal(time.monotonic()) if self.motion is not None else None
        if goal is None:
            self.motion = None
            return
        for servo, position in zip(SERVOS, goal, strict=True):
            msg = Float32()
            msg.data = position
            self.publishers_[servo].publish(msg)


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    gesture_control = None
    try:
        gesture_control = GestureControl()
        gesture_control.start()
        rclpy.spin(gesture_control)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except TorqueError as error:
        assert gesture_control is not None  # only start() raises it
        gesture_control.get_logger().error(str(error))
        sys.exit(1)
    except (ParameterException, ValueError) as error:
        if gesture_control is not None:
            raise
        print(f'gesture_control: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if gesture_control is not None:
            gesture_control.stop()
            gesture_control.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
