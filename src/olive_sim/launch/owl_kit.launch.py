"""The whole Owl Kit: IMU, servos pan and tilt, camera eye, each module its own process."""

from launch import LaunchDescription
from launch.actions import LogInfo
from launch_ros.actions import Node
from olive_sim.kit import OWL_KIT, topic_table


def generate_launch_description():
    nodes = [Node(package='olive_sim', executable=module.executable, output='screen',
                  parameters=[module.parameters] if module.parameters else [])
             for module in OWL_KIT]
    return LaunchDescription([
        LogInfo(msg='Owl Kit simulated modules:\n' + topic_table()),
        *nodes,
    ])
