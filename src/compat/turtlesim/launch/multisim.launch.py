"""Two turtlesim_nodes side by side, in namespaces turtlesim1 and turtlesim2 (as upstream ships)."""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        Node(package='turtlesim', executable='turtlesim_node', namespace=namespace,
             name='sim', output='screen')
        for namespace in ('turtlesim1', 'turtlesim2')
    ])
