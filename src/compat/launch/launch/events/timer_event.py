"""TimerEvent: a TimerAction's period has passed."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.event import Event

if TYPE_CHECKING:
    from launch.actions.timer_action import TimerAction
    from launch.launch_description_entity import LaunchDescriptionEntity


class TimerEvent(Event):
    name = 'launch.events.TimerEvent'

    def __init__(self, *, timer_action: TimerAction, actions: list[LaunchDescriptionEntity]) -> None:
        self.timer_action = timer_action
        self.actions = actions
