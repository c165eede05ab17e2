"""Matchers for ShutdownProcess and SignalProcess: by pid, by name, or the actions themselves."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.events.process.process_targeted_event import ProcessMatcher

if TYPE_CHECKING:
    from launch.actions.execute_local import ExecuteLocal


def matches_pid(*pids: int) -> ProcessMatcher:
    """Process actions whose process has one of these pids right now."""
    def match(action: ExecuteLocal) -> bool:
        process = getattr(action, '_process', None)
        return process is not None and process.pid in pids
    return match


def matches_name(*names: str) -> ProcessMatcher:
    """Process actions whose label (e.g. 'talker-1') is one of names."""
    return lambda action: action.process_description.final_name in names


def matches_executable(*executables: ExecuteLocal) -> ProcessMatcher:
    """Exactly these process actions."""
    return lambda action: any(action is executable for executable in executables)
