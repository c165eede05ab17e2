"""OnActionEventBase: the base of the handlers of the events about actions (process events, completion)."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, TypeAlias

from launch.actions.execute_local import ExecuteLocal
from launch.event_handler import BaseEventHandler, reaction_callable
from launch.events.process.running_process_event import RunningProcessEvent
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from launch.action import Action
    from launch.event import Event
    from launch.events.execution_complete import ExecutionComplete
    from launch.launch_context import LaunchContext


# A reaction: entities, or a callable (event, context) -> entities | None.
SomeActionsOrCallable: TypeAlias = (
    'SomeEntitiesType | Callable[[Event, LaunchContext], SomeEntitiesType | None]')
# Whose events a handler takes: any action's (None), one action's, or those a callable accepts.
TargetAction: TypeAlias = 'LaunchDescriptionEntity | Callable[[Action], object] | None'
# The events that carry the action they are about.
ActionEventType: TypeAlias = 'type[ExecutionComplete] | type[RunningProcessEvent]'


def _action_matcher(target_action: TargetAction, *, processes_only: bool = False
                    ) -> Callable[[Action], bool]:
    """Which actions' events a handler takes: all (None), one action, or those a callable accepts.

    For process events (processes_only) an action target must be a process action
    (ExecuteLocal: ExecuteProcess, Node...), as upstream requires: another action never starts a process.
    """
    if target_action is None:
        return lambda _action: True
    if isinstance(target_action, LaunchDescriptionEntity):
        if processes_only:
            if not isinstance(target_action, ExecuteLocal):
                raise TypeError("target_action must be an ExecuteLocal (ExecuteProcess, Node...) action, "
                                f"a callable taking one, or None; got '{type(target_action).__name__}'")
        return lambda action: action is target_action
    if callable(target_action):
        return lambda action: bool(target_action(action))
    raise TypeError("target_action must be an action, a callable taking an action, or None; got "
                    f"'{type(target_action).__name__}'")


class OnActionEventBase(BaseEventHandler):
    """Reacts to events of one class that belong to the target action(s)."""

    def __init__(self, *, event_type: ActionEventType, on_event: SomeActionsOrCallable,
                 target_action: TargetAction = None, handle_once: bool = False) -> None:
        action_matches = _action_matcher(target_action,
                                         processes_only=issubclass(event_type, RunningProcessEvent))
        super().__init__(
            matcher=lambda event: isinstance(event, event_type) and action_matches(event.action),
            handle_once=handle_once)
        self._on_event = reaction_callable(on_event)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._on_event(event, context)
