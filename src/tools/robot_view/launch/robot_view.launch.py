"""The Owl Kit (its IMU in command mode, so the page can hold it) and robot_view."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from olive_kit.description import OWL_KIT


def generate_launch_description() -> LaunchDescription:
    modules = []
    for module in OWL_KIT:
        parameters = dict(module.parameters)
        if module.module_type == 'imu':
            parameters['motion'] = 'command'  # the page's hand holds the IMU
        modules.append(Node(package='olive_sim', executable=module.executable, output='screen',
                            parameters=[parameters] if parameters else []))
    return LaunchDescription([
        DeclareLaunchArgument('port', default_value='8091', description='robot_view HTTP port'),
        *modules,
        # robot_view prints the page's address when it serves
        Node(package='robot_view', executable='robot_view', output='screen',
             arguments=['--port', LaunchConfiguration('port')]),
    ])
