# An action server shaped like the official ROS 2 tutorials' Python nodes: no try/except around
# rclpy.spin and no clean-up after it (turtlesim's RotateAbsolute stands in for their Fibonacci).
import time

import rclpy
from rclpy.action import ActionServer
from rclpy.node import Node
from turtlesim.action import RotateAbsolute


class RotateActionServer(Node):

    def __init__(self):
        super().__init__('rotate_action_server')
        self._action_server = ActionServer(self, RotateAbsolute, 'rotate', self.execute_callback)

    def execute_callback(self, goal_handle):
        self.get_logger().info('Executing goal...')
        feedback = RotateAbsolute.Feedback()
        for step in range(5):
            feedback.remaining = goal_handle.request.theta * (4 - step) / 5
            goal_handle.publish_feedback(feedback)
            time.sleep(0.1)
        goal_handle.succeed()
        result = RotateAbsolute.Result()
        result.delta = goal_handle.request.theta
        return result


def main(args=None):
    rclpy.init(args=args)
    rotate_action_server = RotateActionServer()
    rclpy.spin(rotate_action_server)


if __name__ == '__main__':
    main()
