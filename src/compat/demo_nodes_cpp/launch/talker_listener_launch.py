"""The talker and the listener of demo_nodes_cpp, together."""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        Node(package='demo_nodes_cpp', executable=name, output='screen') for name in ('talker', 'listener')
    ])
