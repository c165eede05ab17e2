"""ProcessIO: the base of the events about a process's output."""

from __future__ import annotations

from typing import Any

from launch.events.process.running_process_event import RunningProcessEvent


class ProcessIO(RunningProcessEvent):
    """A chunk of a process's output (text is bytes; fd is 1 or 2)."""

    def __init__(self, *, text: bytes, fd: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.text = text
        self.from_stdout = fd == 1
        self.from_stderr = fd == 2
        self.from_stdin = fd == 0
