"""OnIncludeLaunchDescription: the launch service visits included launch descriptions."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.event_handler import EventHandler
from launch.events.include_launch_description import IncludeLaunchDescription as IncludeLaunchDescriptionEvent
from launch.some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext


class OnIncludeLaunchDescription(EventHandler):
    """The launch service's own handler: an included description is visited."""

    def __init__(self) -> None:
        super().__init__(matcher=lambda event: isinstance(event, IncludeLaunchDescriptionEvent))

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return [event.launch_description]  # type: ignore[attr-defined]
