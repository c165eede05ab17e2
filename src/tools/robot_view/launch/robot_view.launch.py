"""The Owl Kit (its IMU in command mode, so the page can hold it) and robot_view.

scene:=ball or scene:=person puts a red ball (ball_speed:=, rad/s; ball_swing:=) or a person
(gesture:=) around the robot, as owl_kit.launch.py does; the page shows them and the ball can be dragged.
"""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from olive_kit.description import OWL_KIT, ROBOT_VIEW_PORT, WEB_PORT


def generate_launch_description() -> LaunchDescription:
    modules = []
    for module in OWL_KIT:
        parameters = {**module.parameters, 'web_port': LaunchConfiguration('web_port')}
        if module.module_type == 'imu':
            parameters['motion'] = 'command'  # the page's hand holds the IMU
        if module.module_type == 'camera':
            parameters.update({name: LaunchConfiguration(name)
                               for name in ('scene', 'ball_speed', 'ball_swing', 'gesture')})
        modules.append(Node(package='olive_sim', executable=module.executable, output='screen',
                            parameters=[parameters] if parameters else []))
    return LaunchDescription([
        DeclareLaunchArgument('port', default_value=str(ROBOT_VIEW_PORT), description='robot_view HTTP port'),
        DeclareLaunchArgument('web_port', default_value=str(WEB_PORT),
                              description="TCP port of every module's own web page (0: no pages)"),
        DeclareLaunchArgument('scene', default_value='landmarks',
                              description="what the camera sees around the robot: landmarks, ball, person"),
        DeclareLaunchArgument('ball_speed', default_value='0.1',
                              description='speed of the red ball around the robot in rad/s (0: still)'),
        DeclareLaunchArgument('ball_swing', default_value='0.0',
                              description='how far the ball swings to either side in rad (0: it goes round)'),
        DeclareLaunchArgument('gesture', default_value='both_hands_down', description="the person's gesture"),
        *modules,
        # robot_view prints the page's address when it serves
        Node(package='robot_view', executable='robot_view', output='screen',
             arguments=['--port', LaunchConfiguration('port')]),
    ])
