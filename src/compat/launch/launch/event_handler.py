"""Event handlers: a matcher deciding which events they take and what they return for one."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from launch.some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext


class BaseEventHandler:
    """Matches events; handle() stores the event in context.locals.event."""

    def __init__(self, *, matcher: Callable[[Event], bool], handle_once: bool = False) -> None:
        self._matcher = matcher
        self.handle_once = handle_once

    def matches(self, event: Event) -> bool:
        return bool(self._matcher(event))

    def describe(self) -> str:
        return type(self).__name__

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        context.extend_locals({'event': event})
        if self.handle_once:
            context.unregister_event_handler(self)
        return None


class EventHandler(BaseEventHandler):
    """Returns a fixed list of entities for every matching event."""

    def __init__(self, *, matcher: Callable[[Event], bool],
                 entities: SomeEntitiesType | None = None, handle_once: bool = False) -> None:
        super().__init__(matcher=matcher, handle_once=handle_once)
        self.entities = entities

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self.entities


class CallbackEventHandler(BaseEventHandler):
    """Calls callback(event, context) for matching events; used by actions for their own events."""

    def __init__(self, *, matcher: Callable[[Event], bool],
                 callback: Callable[[Event, LaunchContext], SomeEntitiesType | None],
                 handle_once: bool = False) -> None:
        super().__init__(matcher=matcher, handle_once=handle_once)
        self._callback = callback

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._callback(event, context)
