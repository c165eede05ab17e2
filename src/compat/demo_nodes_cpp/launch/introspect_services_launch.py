"""The service introspection demo: introspection_service and introspection_client, introspection off.

Switch it on with `ros2 param set /introspection_service service_configure_introspection contents`
(and `client_configure_introspection` on /introspection_client), then `ros2 service echo /add_two_ints`.
"""

from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        Node(package='demo_nodes_cpp', executable=name, output='screen')
        for name in ('introspection_service', 'introspection_client')
    ])
