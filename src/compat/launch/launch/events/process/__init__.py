"""Events about the processes that ExecuteProcess (and Node) run."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeAlias

from launch.event import Event

if TYPE_CHECKING:
    from launch.actions.execute_process import ExecuteProcess

__all__ = [
    'ProcessExited', 'ProcessIO', 'ProcessStarted', 'ProcessStderr', 'ProcessStdin', 'ProcessStdout',
    'ProcessTargetedEvent', 'RunningProcessEvent', 'ShutdownProcess', 'SignalProcess', 'matches_executable',
    'matches_name', 'matches_pid',
]

# Which process actions (ExecuteProcess, Node...) a ShutdownProcess or SignalProcess is for.
ProcessMatcher: TypeAlias = 'Callable[[ExecuteProcess], bool]'


class RunningProcessEvent(Event):
    """Something about one running process; says which action, label, argv, cwd, env and pid."""

    def __init__(self, *, action: ExecuteProcess, name: str, cmd: list[str], cwd: str | None,
                 env: dict[str, str] | None, pid: int) -> None:
        self.action = action
        self.execute_process_action = action
        self.name = name
        self.process_name = name
        self.cmd = cmd
        self.cwd = cwd
        self.env = env
        self.pid = pid


class ProcessStarted(RunningProcessEvent):
    pass


class ProcessExited(RunningProcessEvent):
    def __init__(self, *, returncode: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.returncode = returncode


class ProcessIO(RunningProcessEvent):
    """A chunk of a process's output (text is bytes; fd is 1 or 2)."""

    def __init__(self, *, text: bytes, fd: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.text = text
        self.from_stdout = fd == 1
        self.from_stderr = fd == 2
        self.from_stdin = fd == 0


class ProcessStdout(ProcessIO):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=1, **kwargs)


class ProcessStderr(ProcessIO):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=2, **kwargs)


class ProcessStdin(ProcessIO):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=0, **kwargs)


class ProcessTargetedEvent(Event):
    """An event for the process actions that process_matcher(action) accepts."""

    def __init__(self, *, process_matcher: ProcessMatcher) -> None:
        self.process_matcher = process_matcher


class ShutdownProcess(ProcessTargetedEvent):
    """Stop the matching processes (SIGINT, then the SIGTERM/SIGKILL escalation)."""


class SignalProcess(ProcessTargetedEvent):
    """Send a signal to the matching processes."""

    def __init__(self, *, signal_number: int, process_matcher: ProcessMatcher) -> None:
        super().__init__(process_matcher=process_matcher)
        self.signal = signal_number


# Matchers for ShutdownProcess / SignalProcess: which process actions an event is for.
def matches_pid(*pids: int) -> ProcessMatcher:
    """Process actions whose process has one of these pids right now."""
    def match(action: ExecuteProcess) -> bool:
        process = getattr(action, '_process', None)
        return process is not None and process.pid in pids
    return match


def matches_name(*names: str) -> ProcessMatcher:
    """Process actions whose label (e.g. 'talker-1') is one of names."""
    return lambda action: action.process_description.final_name in names


def matches_executable(*executables: ExecuteProcess) -> ProcessMatcher:
    """Exactly these process actions."""
    return lambda action: any(action is executable for executable in executables)
