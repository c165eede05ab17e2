"""mimic: node `turtle_mimic`, replays one turtle's motion on another.

For every pose on `input/pose` it publishes a Twist on `output/cmd_vel` with linear.x = the pose's
linear_velocity (a magnitude, so a reversing leader is mimicked driving forwards) and angular.z =
its angular_velocity. Remap both names, e.g. under multisim.launch.py.
"""

from __future__ import annotations

from geometry_msgs.msg import Twist
from owl_common.run import spin_node
from rclpy.node import Node
from turtlesim.msg import Pose

HUMBLE_QOS_DEPTH = 1


def twist_for(pose: Pose) -> Twist:
    """The Twist that repeats a pose's motion: its speed forwards and its turn rate."""
    twist = Twist()
    twist.linear.x = float(pose.linear_velocity)
    twist.angular.z = float(pose.angular_velocity)
    return twist


class Mimic(Node):
    """Node `turtle_mimic`: a Twist on output/cmd_vel for every Pose on input/pose."""

    def __init__(self) -> None:
        super().__init__('turtle_mimic')
        self._publisher = self.create_publisher(Twist, 'output/cmd_vel', HUMBLE_QOS_DEPTH)
        self.create_subscription(Pose, 'input/pose', self._on_pose, HUMBLE_QOS_DEPTH)

    def _on_pose(self, pose: Pose) -> None:
        self._publisher.publish(twist_for(pose))


def main(args: list[str] | None = None) -> None:
    """Run the node until Ctrl-C; args is the command line rclpy reads (None: sys.argv)."""
    spin_node(Mimic, args)


if __name__ == '__main__':
    main()
