"""Executable: what a process action runs, once prepared."""

from __future__ import annotations


class Executable:
    """The final argv, label, working directory and environment of a process, once prepared."""

    def __init__(self) -> None:
        self.final_cmd: list[str] | None = None
        self.final_name: str | None = None
        self.final_cwd: str | None = None
        self.final_env: dict[str, str] | None = None

    @property
    def name(self) -> str | None:
        return self.final_name
