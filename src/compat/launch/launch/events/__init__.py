"""Events of the launch system itself."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from launch.event import Event
from launch.events import process

if TYPE_CHECKING:
    from launch.action import Action
    from launch.actions.timer_action import TimerAction
    from launch.launch_description import LaunchDescription
    from launch.launch_description_entity import LaunchDescriptionEntity

__all__ = [
    'ExecutionComplete', 'IncludeLaunchDescription', 'Shutdown', 'TimerEvent', 'matches_action',
    'process',
]


class Shutdown(Event):
    """Ask the launch to shut down: processes are stopped, timers cancelled, then launch exits."""

    name = 'launch.events.Shutdown'

    def __init__(self, *, reason: str = 'reason not given', due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint


class TimerEvent(Event):
    name = 'launch.events.TimerEvent'

    def __init__(self, *, timer_action: TimerAction, actions: list[LaunchDescriptionEntity]) -> None:
        self.timer_action = timer_action
        self.actions = actions


class ExecutionComplete(Event):
    name = 'launch.events.ExecutionComplete'

    def __init__(self, *, action: Action) -> None:
        self.action = action


class IncludeLaunchDescription(Event):
    name = 'launch.events.IncludeLaunchDescription'

    def __init__(self, launch_description: LaunchDescription) -> None:
        self.launch_description = launch_description


def matches_action(target_action: Action) -> Callable[[Action], bool]:
    """A matcher for process events and process-targeting events of exactly this action."""
    return lambda action: action is target_action
