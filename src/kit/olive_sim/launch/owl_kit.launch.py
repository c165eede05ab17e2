"""The whole Owl Kit: IMU, servos pan and tilt, camera eye, each module its own process.

Each has its own web page (http://127.42.0.N:<web_port>/ for the module at 10.42.0.N). The camera
sees the landmarks around the robot, plus a red ball (scene:=ball, moving at ball_speed rad/s) or a
person making a gesture (scene:=person gesture:=both_hands_up), sections 4.6 and 4.7.
"""

import math

from launch import LaunchContext, LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from olive_kit.description import OWL_KIT, WEB_PORT, address_table, topic_table
from olive_sim.scene_model import BALL_MAX_SPEED, GESTURE_NAMES, SCENES


def scene_parameters(context: LaunchContext) -> dict[str, object]:
    """The camera's scene, ball_speed and gesture from the launch arguments; ValueError if one is wrong."""
    scene = LaunchConfiguration('scene').perform(context)
    if scene not in SCENES:
        raise ValueError(f"scene must be one of {', '.join(SCENES)}, got '{scene}'")
    text = LaunchConfiguration('ball_speed').perform(context)
    try:
        speed = float(text)
    except ValueError:
        speed = math.nan
    if not 0.0 <= speed <= BALL_MAX_SPEED:
        raise ValueError(f"ball_speed must be a number of rad/s from 0 (still) to {BALL_MAX_SPEED}, "
                         f"got '{text}'")
    gesture = LaunchConfiguration('gesture').perform(context)
    if gesture not in GESTURE_NAMES:
        raise ValueError(f"gesture must be one of {', '.join(GESTURE_NAMES)}, got '{gesture}'")
    return {'scene': scene, 'ball_speed': speed, 'gesture': gesture}


def modules(context: LaunchContext) -> list[LaunchDescriptionEntity]:
    port = LaunchConfiguration('web_port').perform(context)
    if not port.isdigit() or int(port) > 65535:
        raise ValueError(f"web_port must be a TCP port number 0..65535 (0: no pages), got '{port}'")
    scene = scene_parameters(context)
    nodes = [Node(package='olive_sim', executable=module.executable, output='screen',
                  parameters=[{**module.parameters, 'web_port': int(port),
                               **(scene if module.module_type == 'camera' else {})}])
             for module in OWL_KIT]
    return [LogInfo(msg='Owl Kit simulated modules:\n' + topic_table()),
            LogInfo(msg='Owl Kit module addresses (a page moves with an IP changed on it):\n'
                        + address_table(port)),
            *nodes]


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('web_port', default_value=str(WEB_PORT),
                              description="TCP port of every module's web page (0: no pages)"),
        DeclareLaunchArgument('scene', default_value='landmarks',
                              description=f"What the camera sees around the robot: {', '.join(SCENES)}"),
        DeclareLaunchArgument('ball_speed', default_value='0.1',
                              description='Speed of the red ball around the robot in rad/s (0: still)'),
        DeclareLaunchArgument('gesture', default_value=GESTURE_NAMES[0],
                              description=f"The person's gesture: {', '.join(GESTURE_NAMES)}"),
        OpaqueFunction(function=modules),
    ])
