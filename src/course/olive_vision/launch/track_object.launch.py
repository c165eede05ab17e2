"""Section 4.6: track_object and display_camera together; the kit (olive_sim: scene:=ball) beside it.

The head keeps the red ball in the middle of the picture and the window shows what the camera sees.
ros2 launch olive_vision track_object.launch.py [image_topic:=...] [search:=true]
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('image_topic', default_value='/olive/camera/eye/image/compressed',
                              description='sensor_msgs/msg/CompressedImage topic of the camera'),
        DeclareLaunchArgument('search', default_value='false',
                              description='sweep the pan servo to find the ball when it is lost'),
        Node(
            package='olive_vision',
            executable='track_object',
            name='track_object',
            parameters=[{'image_topic': LaunchConfiguration('image_topic'),
                         'search': LaunchConfiguration('search')}],
        ),
        Node(
            package='olive_camera',
            executable='display_camera',
            name='display_camera',
            parameters=[{'image_topic': LaunchConfiguration('image_topic')}],
        ),
    ])
