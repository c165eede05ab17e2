"""OnProcessStart: react to processes starting."""

from __future__ import annotations

from launch.event_handlers.on_action_event_base import (
    OnActionEventBase,
    SomeActionsOrCallable,
    TargetAction,
)
from launch.events.process.process_started import ProcessStarted


class OnProcessStart(OnActionEventBase):
    def __init__(self, *, target_action: TargetAction = None, on_start: SomeActionsOrCallable,
                 handle_once: bool = False) -> None:
        super().__init__(event_type=ProcessStarted, on_event=on_start, target_action=target_action,
                         handle_once=handle_once)
