"""Two turtlesim_nodes side by side, /turtlesim1/turtlesim and /turtlesim2/turtlesim (as upstream ships)."""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        Node(package='turtlesim', executable='turtlesim_node', namespace=namespace, output='screen')
        for namespace in ('turtlesim1', 'turtlesim2')
    ])
