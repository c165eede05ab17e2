"""ProcessTargetedEvent: the base of the events for some process actions."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, TypeAlias

from launch.event import Event

if TYPE_CHECKING:
    from launch.actions.execute_local import ExecuteLocal


# Which process actions (ExecuteProcess, Node...) a ShutdownProcess or SignalProcess is for.
ProcessMatcher: TypeAlias = 'Callable[[ExecuteLocal], bool]'


class ProcessTargetedEvent(Event):
    """An event for the process actions that process_matcher(action) accepts."""

    def __init__(self, *, process_matcher: ProcessMatcher) -> None:
        self.process_matcher = process_matcher
