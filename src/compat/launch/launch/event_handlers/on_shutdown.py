"""OnShutdown: react to the launch shutting down."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.event_handler import BaseEventHandler, reaction_callable
from launch.event_handlers.on_action_event_base import SomeActionsOrCallable
from launch.events.shutdown import Shutdown
from launch.some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext


class OnShutdown(BaseEventHandler):
    def __init__(self, *, on_shutdown: SomeActionsOrCallable, handle_once: bool = False) -> None:
        super().__init__(matcher=lambda event: isinstance(event, Shutdown), handle_once=handle_once)
        self._on_shutdown = reaction_callable(on_shutdown)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._on_shutdown(event, context)
