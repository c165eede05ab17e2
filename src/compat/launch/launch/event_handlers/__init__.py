"""Event handlers for process events, shutdown, completion of actions and includes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, TypeAlias

from launch.event_handler import BaseEventHandler, EventHandler, SomeEntitiesType
from launch.events.execution_complete import ExecutionComplete
from launch.events.include_launch_description import IncludeLaunchDescription as IncludeLaunchDescriptionEvent
from launch.events.process.process_exited import ProcessExited
from launch.events.process.process_io import ProcessIO
from launch.events.process.process_started import ProcessStarted
from launch.events.process.running_process_event import RunningProcessEvent
from launch.events.shutdown import Shutdown
from launch.launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from launch.action import Action
    from launch.event import Event
    from launch.launch_context import LaunchContext

__all__ = [
    'EventHandler',
    'OnActionEventBase',
    'OnExecutionComplete',
    'OnIncludeLaunchDescription',
    'OnProcessExit',
    'OnProcessIO',
    'OnProcessStart',
    'OnShutdown',
    'event_named',
]

# A reaction: entities, or a callable (event, context) -> entities | None.
SomeActionsOrCallable: TypeAlias = (
    'SomeEntitiesType | Callable[[Event, LaunchContext], SomeEntitiesType | None]')
# Whose events a handler takes: any action's (None), one action's, or those a callable accepts.
TargetAction: TypeAlias = 'LaunchDescriptionEntity | Callable[[Action], object] | None'
# The events that carry the action they are about.
ActionEventType: TypeAlias = 'type[ExecutionComplete] | type[RunningProcessEvent]'


def _entities_or_callable(on_event: SomeActionsOrCallable
                          ) -> Callable[[Event, LaunchContext], SomeEntitiesType | None]:
    """Check a reaction once, at construction, and turn it into a callable."""
    if callable(on_event) and not isinstance(on_event, LaunchDescriptionEntity):
        return on_event
    entities = [on_event] if isinstance(on_event, LaunchDescriptionEntity) else list(on_event)
    for entity in entities:
        if not isinstance(entity, LaunchDescriptionEntity):
            raise TypeError(f"expected launch description entities, got '{type(entity).__name__}'")
    return lambda _event, _context: entities


def _action_matcher(target_action: TargetAction, *, processes_only: bool = False
                    ) -> Callable[[Action], bool]:
    """Which actions' events a handler takes: all (None), one action, or those a callable accepts.

    For process events (processes_only) an action target must be a process action
    (ExecuteProcess, Node...), as upstream requires: another action never starts a process.
    """
    if target_action is None:
        return lambda _action: True
    if isinstance(target_action, LaunchDescriptionEntity):
        if processes_only:
            from launch.actions.execute_process import ExecuteProcess

            if not isinstance(target_action, ExecuteProcess):
                raise TypeError("target_action must be an ExecuteProcess (or Node) action, a callable "
                                f"taking one, or None; got '{type(target_action).__name__}'")
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
        self._on_event = _entities_or_callable(on_event)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._on_event(event, context)


class OnProcessStart(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_start: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ProcessStarted, on_event=on_start, target_action=target_action,
                         handle_once=handle_once)


class OnProcessExit(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_exit: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ProcessExited, on_event=on_exit, target_action=target_action,
                         handle_once=handle_once)


class OnExecutionComplete(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_completion: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ExecutionComplete, on_event=on_completion,
                         target_action=target_action, handle_once=handle_once)


class OnProcessIO(BaseEventHandler):
    """Callbacks get the ProcessIO event only (text is bytes)."""

    def __init__(self, *, target_action: TargetAction = None,
                 on_stdin: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 on_stdout: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 on_stderr: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 handle_once: bool = False) -> None:
        action_matches = _action_matcher(target_action, processes_only=True)
        self._callbacks = {0: on_stdin, 1: on_stdout, 2: on_stderr}
        super().__init__(
            matcher=lambda event: (isinstance(event, ProcessIO) and action_matches(event.action)
                                   and self._callback(event) is not None),
            handle_once=handle_once)

    def _callback(self, event: ProcessIO) -> Callable[[ProcessIO], SomeEntitiesType | None] | None:
        fd = 1 if event.from_stdout else 2 if event.from_stderr else 0
        return self._callbacks[fd]

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        if not isinstance(event, ProcessIO):  # the matcher lets only ProcessIO through
            return None
        callback = self._callback(event)
        return callback(event) if callback is not None else None


class OnShutdown(BaseEventHandler):
    def __init__(self, *, on_shutdown: SomeActionsOrCallable, handle_once: bool = False) -> None:
        super().__init__(matcher=lambda event: isinstance(event, Shutdown), handle_once=handle_once)
        self._on_shutdown = _entities_or_callable(on_shutdown)

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return self._on_shutdown(event, context)


class OnIncludeLaunchDescription(EventHandler):
    """The launch service's own handler: an included description is visited."""

    def __init__(self) -> None:
        super().__init__(matcher=lambda event: isinstance(event, IncludeLaunchDescriptionEvent))

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        super().handle(event, context)
        return [event.launch_description]  # type: ignore[attr-defined]


# Last: the module has no imports from this package, but upstream exports it here.
from launch.event_handlers.event_named import event_named  # noqa: E402
