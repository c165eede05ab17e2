"""ProcessStdout: a chunk of a process's standard output."""

from __future__ import annotations

from typing import Any

from launch.events.process.process_io import ProcessIO


class ProcessStdout(ProcessIO):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=1, **kwargs)
