"""PushEnvironment: save the environment; the matching PopEnvironment restores it."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.action import Action

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class PushEnvironment(Action):
    def execute(self, context: LaunchContext) -> None:
        context._push_environment()
