"""Event handlers: a matcher deciding which events they take and what they return for one."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from launch.launch_description_entity import LaunchDescriptionEntity
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


def reaction_callable(on_event: SomeEntitiesType | Callable[[Event, LaunchContext], SomeEntitiesType | None]
                      ) -> Callable[[Event, LaunchContext], SomeEntitiesType | None]:
    """A handler's reaction (entities, or a callable (event, context)), checked once, as a callable."""
    if callable(on_event) and not isinstance(on_event, LaunchDescriptionEntity):
        return on_event
    entities = [on_event] if isinstance(on_event, LaunchDescriptionEntity) else list(on_event)
    for entity in entities:
        if not isinstance(entity, LaunchDescriptionEntity):
            raise TypeError(f"expected launch description entities, got '{type(entity).__name__}'")
    return lambda _event, _context: entities
