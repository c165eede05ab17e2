"""The actions of launch_ros."""

from launch_ros.actions.composable_node_container import ComposableNodeContainer, LoadComposableNodes
from launch_ros.actions.lifecycle_node import LifecycleNode
from launch_ros.actions.lifecycle_transition import LifecycleTransition
from launch_ros.actions.node import Node
from launch_ros.actions.ros_timer import ROSTimer, RosTimer
from launch_ros.actions.scoped import (
    PushROSNamespace,
    PushRosNamespace,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
)
from launch_ros.actions.set_ros_log_dir import SetROSLogDir
from launch_ros.actions.set_use_sim_time import SetUseSimTime

__all__ = [
    'ComposableNodeContainer', 'LifecycleNode', 'LifecycleTransition', 'LoadComposableNodes', 'Node',
    'PushROSNamespace', 'PushRosNamespace', 'ROSTimer', 'RosTimer', 'SetParameter', 'SetParametersFromFile',
    'SetROSLogDir', 'SetRemap', 'SetUseSimTime',
]
