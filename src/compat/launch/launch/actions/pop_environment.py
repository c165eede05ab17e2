"""PopEnvironment: restore the environment the matching PushEnvironment saved."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.action import Action

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class PopEnvironment(Action):
    def execute(self, context: LaunchContext) -> None:
        context._pop_environment()
