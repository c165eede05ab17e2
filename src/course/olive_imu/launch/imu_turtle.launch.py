"""Section 4.3.2 extra: turtlesim_node and imu_turtle together; start an IMU (or olive_sim's kit) beside it.

ros2 launch olive_imu imu_turtle.launch.py [imu_topic:=...] [speed_factor:=...] [turn_factor:=...]
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('imu_topic', default_value='/olive/imu/x1684267976913/imu',
                              description='sensor_msgs/msg/Imu topic of the IMU'),
        DeclareLaunchArgument('speed_factor', default_value='1.5',
                              description='turtle speed per radian of pitch, m/s per rad'),
        DeclareLaunchArgument('turn_factor', default_value='1.5',
                              description='turtle turn rate per radian of yaw, rad/s per rad'),
        Node(
            package='turtlesim',
            executable='turtlesim_node',
            name='turtlesim',
        ),
        Node(
            package='olive_imu',
            executable='imu_turtle',
            name='imu_turtle',
            parameters=[{
                'imu_topic': LaunchConfiguration('imu_topic'),
                'speed_factor': LaunchConfiguration('speed_factor'),
                'turn_factor': LaunchConfiguration('turn_factor'),
            }],
        ),
    ])
