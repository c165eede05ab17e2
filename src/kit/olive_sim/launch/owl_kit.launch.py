"""The whole Owl Kit: IMU, servos pan and tilt, camera eye, each module its own process.

Each has its own web page (http://127.42.0.N:<web_port>/ for the module at 10.42.0.N). The camera
sees the landmarks around the robot, plus a red ball (scene:=ball, moving at ball_speed rad/s round
the robot, or to and fro in front of it with ball_swing:= rad to either side) or a person making a
gesture (scene:=person gesture:=both_hands_up), sections 4.6 and 4.7.
"""

import math

from launch import LaunchContext, LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from olive_kit.description import OWL_KIT, WEB_PORT, address_table, topic_table
from olive_sim.scene_model import BALL_MAX_SPEED, BALL_MAX_SWING, GESTURE_NAMES, SCENES


def number_argument(context: LaunchContext, name: str, high: float, meaning: str) -> float:
    """The launch argument name as a number from 0 to high; ValueError saying what it means if not."""
    text = LaunchConfiguration(name).perform(context)
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0.0 <= value <= high:
        raise ValueError(f"{name} must be a number of {meaning} to {round(high, 4)}, got '{text}'")
    return value


def scene_parameters(context: LaunchContext) -> dict[str, object]:
    """The camera's scene, ball_speed, ball_swing and gesture from the launch arguments; ValueError if bad."""
    scene = LaunchConfiguration('scene').perform(context)
    if scene not in SCENES:
        raise ValueError(f"scene must be one of {', '.join(SCENES)}, got '{scene}'")
    speed = number_argument(context, 'ball_speed', BALL_MAX_SPEED, 'rad/s from 0 (still)')
    swing = number_argument(context, 'ball_swing', BALL_MAX_SWING, 'rad from 0 (round the robot)')
    gesture = LaunchConfiguration('gesture').perform(context)
    if gesture not in GESTURE_NAMES:
        raise ValueError(f"gesture must be one of {', '.join(GESTURE_NAMES)}, got '{gesture}'")
    return {'scene': scene, 'ball_speed': speed, 'ball_swing': swing, 'gesture': gesture}


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
        DeclareLaunchArgument('ball_swing', default_value='0.0',
                              description='How far the ball swings to either side in front of the robot, '
                                          'in rad (0: it goes round the robot)'),
        DeclareLaunchArgument('gesture', default_value=GESTURE_NAMES[0],
                              description=f"The person's gesture: {', '.join(GESTURE_NAMES)}"),
        OpaqueFunction(function=modules),
    ])
