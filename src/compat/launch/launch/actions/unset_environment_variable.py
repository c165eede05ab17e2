"""UnsetEnvironmentVariable (`<unset_env>`): remove an environment variable of launch."""

from __future__ import annotations

from collections.abc import MutableMapping
from typing import TYPE_CHECKING

from launch.actions.named_value_actions import UnsetNamedValue
from launch.frontend.expose import expose_action

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


@expose_action('unset_env')
class UnsetEnvironmentVariable(UnsetNamedValue):
    @staticmethod
    def entries(context: LaunchContext) -> MutableMapping[str, str]:
        return context.environment
