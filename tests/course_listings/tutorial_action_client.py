# Goals for tutorial_action_server.py, one after another, so that a Ctrl-C may land in a goal.
import rclpy
from rclpy.action import ActionClient
from rclpy.node import Node
from turtlesim.action import RotateAbsolute


class RotateActionClient(Node):

    def __init__(self):
        super().__init__('rotate_action_client')
        self._action_client = ActionClient(self, RotateAbsolute, 'rotate')
        self.timer = self.create_timer(0.2, self.send_goal)

    def send_goal(self):
        if self._action_client.server_is_ready():
            goal = RotateAbsolute.Goal()
            goal.theta = 1.0
            self._action_client.send_goal_async(goal)


def main(args=None):
    rclpy.init(args=args)
    rotate_action_client = RotateActionClient()
    try:
        rclpy.spin(rotate_action_client)
    except KeyboardInterrupt:
        pass
    rotate_action_client.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
