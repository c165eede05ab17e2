"""ProcessStderr: a chunk of a process's standard error."""

from __future__ import annotations

from typing import Any

from launch.events.process.process_io import ProcessIO


class ProcessStderr(ProcessIO):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__(fd=2, **kwargs)
