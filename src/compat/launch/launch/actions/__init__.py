"""The actions of launch."""

from launch.actions.environment_actions import (
    AppendEnvironmentVariable,
    PopEnvironment,
    PushEnvironment,
    ResetEnvironment,
    SetEnvironmentVariable,
    UnsetEnvironmentVariable,
)
from launch.actions.event_actions import (
    EmitEvent,
    LogInfo,
    OpaqueFunction,
    RegisterEventHandler,
    Shutdown,
    UnregisterEventHandler,
)
from launch.actions.execute_process import ExecuteProcess
from launch.actions.group_action import GroupAction
from launch.actions.include_launch_description import IncludeLaunchDescription
from launch.actions.launch_configuration_actions import (
    DeclareLaunchArgument,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    SetLaunchConfiguration,
    UnsetLaunchConfiguration,
)
from launch.actions.opaque_coroutine import OpaqueCoroutine
from launch.actions.reset_launch_configurations import ResetLaunchConfigurations
from launch.actions.timer_action import TimerAction

# Upstream's name for the process-running base class.
ExecuteLocal = ExecuteProcess

__all__ = [
    'AppendEnvironmentVariable', 'DeclareLaunchArgument', 'EmitEvent', 'ExecuteLocal', 'ExecuteProcess',
    'GroupAction', 'IncludeLaunchDescription', 'LogInfo', 'OpaqueCoroutine', 'OpaqueFunction',
    'PopEnvironment', 'PopLaunchConfigurations', 'PushEnvironment', 'PushLaunchConfigurations',
    'RegisterEventHandler', 'ResetEnvironment', 'ResetLaunchConfigurations', 'SetEnvironmentVariable',
    'SetLaunchConfiguration', 'Shutdown', 'TimerAction', 'UnregisterEventHandler',
    'UnsetEnvironmentVariable', 'UnsetLaunchConfiguration',
]
