"""OnExecutionComplete: react to actions finishing."""

from __future__ import annotations

from launch.event_handlers.on_action_event_base import (
    OnActionEventBase,
    SomeActionsOrCallable,
    TargetAction,
)
from launch.events.execution_complete import ExecutionComplete


class OnExecutionComplete(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_completion: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ExecutionComplete, on_event=on_completion,
                         target_action=target_action, handle_once=handle_once)
