"""RunningProcessEvent: the base of the events about one running process."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.event import Event

if TYPE_CHECKING:
    from launch.actions.execute_local import ExecuteLocal


class RunningProcessEvent(Event):
    """Something about one running process; says which action, label, argv, cwd, env and pid."""

    def __init__(self, *, action: ExecuteLocal, name: str, cmd: list[str], cwd: str | None,
                 env: dict[str, str] | None, pid: int) -> None:
        self.action = action
        self.execute_process_action = action
        self.name = name
        self.process_name = name
        self.cmd = cmd
        self.cwd = cwd
        self.env = env
        self.pid = pid
