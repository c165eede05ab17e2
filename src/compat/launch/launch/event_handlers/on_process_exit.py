"""OnProcessExit: react to processes exiting."""

from __future__ import annotations

from launch.event_handlers.on_action_event_base import (
    OnActionEventBase,
    SomeActionsOrCallable,
    TargetAction,
)
from launch.events.process.process_exited import ProcessExited


class OnProcessExit(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_exit: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ProcessExited, on_event=on_exit, target_action=target_action,
                         handle_once=handle_once)
