"""Section 4.5 extra: imu_control_robot and display_camera together; start the kit (or olive_sim's) beside it.

The IMU points the camera's pan/tilt head and the window shows what the camera sees.
ros2 launch olive_camera robot_camera.launch.py [imu_topic:=...] [image_topic:=...]
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('imu_topic', default_value='/olive/imu/x1684267976913/imu',
                              description='sensor_msgs/msg/Imu topic of the IMU'),
        DeclareLaunchArgument('image_topic', default_value='/olive/camera/eye/image/compressed',
                              description='sensor_msgs/msg/CompressedImage topic of the camera'),
        Node(
            package='olive_servo',
            executable='imu_control_robot',
            name='imu_control_robot',
            parameters=[{'imu_topic': LaunchConfiguration('imu_topic')}],
        ),
        Node(
            package='olive_camera',
            executable='display_camera',
            name='display_camera',
            parameters=[{'image_topic': LaunchConfiguration('image_topic')}],
        ),
    ])
