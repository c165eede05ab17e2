"""The actions of launch_ros."""

from launch_ros.actions.node import Node
from launch_ros.actions.ros_timer import ROSTimer, RosTimer
from launch_ros.actions.scoped import (
    PushROSNamespace,
    PushRosNamespace,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
)

__all__ = [
    'Node', 'PushROSNamespace', 'PushRosNamespace', 'ROSTimer', 'RosTimer', 'SetParameter',
    'SetParametersFromFile', 'SetRemap',
]
