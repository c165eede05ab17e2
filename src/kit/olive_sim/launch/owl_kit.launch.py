"""The whole Owl Kit: IMU, servos pan and tilt, camera eye, each module its own process.

Each has its own web page (http://127.42.0.N:<web_port>/ for the module at 10.42.0.N).
"""

from launch import LaunchContext, LaunchDescription
from launch.actions import DeclareLaunchArgument, LogInfo, OpaqueFunction
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from olive_kit.description import OWL_KIT, WEB_PORT, address_table, topic_table


def modules(context: LaunchContext) -> list[LaunchDescriptionEntity]:
    port = LaunchConfiguration('web_port').perform(context)
    if not port.isdigit() or int(port) > 65535:
        raise ValueError(f"web_port must be a TCP port number 0..65535 (0: no pages), got '{port}'")
    nodes = [Node(package='olive_sim', executable=module.executable, output='screen',
                  parameters=[{**module.parameters, 'web_port': int(port)}])
             for module in OWL_KIT]
    return [LogInfo(msg='Owl Kit simulated modules:\n' + topic_table()),
            LogInfo(msg='Owl Kit module addresses (a page moves with an IP changed on it):\n'
                        + address_table(port)),
            *nodes]


def generate_launch_description() -> LaunchDescription:
    return LaunchDescription([
        DeclareLaunchArgument('web_port', default_value=str(WEB_PORT),
                              description="TCP port of every module's web page (0: no pages)"),
        OpaqueFunction(function=modules),
    ])
