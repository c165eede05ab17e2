"""ResetEnvironment (`<reset_env>`): back to the environment launch started with."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('reset_env')
class ResetEnvironment(Action):
    """Back to the environment launch started with."""

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        return cls, {}

    def execute(self, context: LaunchContext) -> None:
        context._reset_environment()
