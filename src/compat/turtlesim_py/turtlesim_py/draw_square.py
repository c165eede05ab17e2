"""draw_square: node `draw_square`, drives turtle1 around a 2 m square (the fixed behaviour).

It resets the simulator once, then a 16 ms timer runs FORWARD -> STOP_FORWARD -> TURN ->
STOP_TURN: drive 1 m/s until within 0.1 m / 0.01 rad of the goal, stop until the pose reports
standstill, turn at 0.4 rad/s to the next right angle, stop, and so on.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

from geometry_msgs.msg import Twist
from owl_common.run import spin_node
from rclpy.node import Node
from rclpy.task import Future
from std_srvs.srv import Empty
from turtlesim.msg import Pose

# The literal upstream's draw_square uses.
PI = 3.141592
SIDE = 2.0  # m
FORWARD_SPEED = 1.0  # m/s
TURN_SPEED = 0.4  # rad/s
HUMBLE_QOS_DEPTH = 1


class State(enum.Enum):
    """The four phases of one side of the square, in the order the timer goes through them."""

    FORWARD = 0
    STOP_FORWARD = 1
    TURN = 2
    STOP_TURN = 3


@dataclass(frozen=True)
class Goal:
    """Where a phase should end: position in m and heading in rad, in the simulator's frame."""

    x: float
    y: float
    theta: float


def wrap(angle: float) -> float:
    """Angle into [-PI, PI)."""
    return angle - 2.0 * PI * math.floor((angle + PI) / (2.0 * PI))


def reached(pose: Pose, goal: Goal) -> bool:
    """Whether the pose is within 0.1 m and 0.01 rad of the goal, as upstream checks (angles not wrapped)."""
    return (abs(pose.x - goal.x) < 0.1 and abs(pose.y - goal.y) < 0.1
            and abs(pose.theta - goal.theta) < 0.01)


def stopped(pose: Pose) -> bool:
    """Whether the turtle has come to a standstill (both velocities below 0.0001)."""
    return pose.linear_velocity < 0.0001 and pose.angular_velocity < 0.0001


def goal_ahead(pose: Pose) -> Goal:
    """The goal SIDE metres straight ahead of the pose, with the same heading."""
    return Goal(pose.x + SIDE * math.cos(pose.theta), pose.y + SIDE * math.sin(pose.theta), pose.theta)


def goal_turned(pose: Pose) -> Goal:
    """The goal a quarter turn to the left of the pose, on the same spot."""
    return Goal(pose.x, pose.y, wrap(pose.theta + PI / 2.0))


def step(state: State, pose: Pose, goal: Goal) -> tuple[State, Goal, tuple[float, float], bool]:
    """One timer tick: (next state, next goal, (linear, angular) to command, goal reached?)."""
    if state is State.FORWARD:
        if reached(pose, goal):
            return State.STOP_FORWARD, goal, (0.0, 0.0), False
        return state, goal, (FORWARD_SPEED, 0.0), False
    if state is State.TURN:
        if reached(pose, goal):
            return State.STOP_TURN, goal, (0.0, 0.0), False
        return state, goal, (0.0, TURN_SPEED), False
    if not stopped(pose):
        return state, goal, (0.0, 0.0), False
    if state is State.STOP_FORWARD:
        return State.TURN, goal_turned(pose), (0.0, 0.0), True
    return State.FORWARD, goal_ahead(pose), (0.0, 0.0), True


class DrawSquare(Node):
    """Node `draw_square`: resets the simulator, then drives turtle1 around the square with a 16 ms timer."""

    def __init__(self) -> None:
        super().__init__('draw_square')
        self._cmd = self.create_publisher(Twist, 'turtle1/cmd_vel', HUMBLE_QOS_DEPTH)
        self.create_subscription(Pose, 'turtle1/pose', self._on_pose, HUMBLE_QOS_DEPTH)
        self._reset = self.create_client(Empty, 'reset')
        self._pose: Pose | None = None
        self._goal: Goal | None = None
        self._state = State.FORWARD
        self._reset_sent = False
        self._ready = False  # poses count only once the reset has been answered
        self.create_timer(0.016, self._tick)

    def _on_reset_done(self, _future: Future) -> None:
        self._ready = True

    def _on_pose(self, pose: Pose) -> None:
        if not self._ready:
            return
        self._pose = pose
        if self._goal is None:
            self._goal = goal_ahead(pose)
            self._log_goal(self._goal)

    def _tick(self) -> None:
        if not self._reset_sent:
            if self._reset.service_is_ready():
                self._reset_sent = True
                self._reset.call_async(Empty.Request()).add_done_callback(self._on_reset_done)
            return
        if self._pose is None or self._goal is None:
            return
        self._state, goal, (linear, angular), reached_goal = step(self._state, self._pose, self._goal)
        if reached_goal:
            self.get_logger().info('Reached goal')
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        self._cmd.publish(twist)
        if goal is not self._goal:
            self._goal = goal
            self._log_goal(goal)

    def _log_goal(self, g: Goal) -> None:
        self.get_logger().info(f'New goal [{g.x:f} {g.y:f}, {g.theta:f}]')


def main(args: list[str] | None = None) -> None:
    """Run the node until Ctrl-C; args is the command line rclpy reads (None: sys.argv)."""
    spin_node(DrawSquare, args)


if __name__ == '__main__':
    main()
