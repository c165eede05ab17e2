"""Section 4.7: gesture_control and the gesture app's picture; the kit (olive_sim: scene:=person) beside it.

The head answers your gestures and the window shows the skeleton the camera's gesture app sees.
ros2 launch olive_vision gesture_control.launch.py [target:=turtle] [gesture_topic:=...] [image_topic:=...]
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('gesture_topic', default_value='/olive/camera/eye/tpu/gesture',
                              description="std_msgs/msg/String topic of the camera's gesture app"),
        DeclareLaunchArgument('image_topic', default_value='/olive/camera/eye/tpu/compressed',
                              description="the gesture app's picture with the skeleton it sees"),
        DeclareLaunchArgument('target', default_value='head',
                              description="what the gestures move: 'head' or 'turtle' (turtlesim)"),
        Node(
            package='olive_vision',
            executable='gesture_control',
            name='gesture_control',
            parameters=[{'gesture_topic': LaunchConfiguration('gesture_topic'),
                         'target': LaunchConfiguration('target')}],
        ),
        Node(
            package='olive_camera',
            executable='display_camera',
            name='display_camera',
            parameters=[{'image_topic': LaunchConfiguration('image_topic')}],
        ),
    ])
