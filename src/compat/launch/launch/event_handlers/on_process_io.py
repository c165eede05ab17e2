"""OnProcessIO: react to the output of processes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from launch.event_handler import BaseEventHandler
from launch.event_handlers.on_action_event_base import TargetAction, _action_matcher
from launch.events.process.process_io import ProcessIO
from launch.some_entities_type import SomeEntitiesType

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext


class OnProcessIO(BaseEventHandler):
    """Callbacks get the ProcessIO event only (text is bytes); all three are optional."""

    def __init__(self, *, target_action: TargetAction = None,
                 on_stdin: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 on_stdout: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 on_stderr: Callable[[ProcessIO], SomeEntitiesType | None] | None = None,
                 handle_once: bool = False) -> None:
        action_matches = _action_matcher(target_action, processes_only=True)
        self._callbacks = {0: on_stdin, 1: on_stdout, 2: on_stderr}
        # As upstream, the IO events of the target match even without a callback for their stream
        # (so handle_once is used up by the first one).
        super().__init__(
            matcher=lambda event: isinstance(event, ProcessIO) and action_matches(event.action),
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
