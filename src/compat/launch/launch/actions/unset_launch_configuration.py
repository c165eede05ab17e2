"""UnsetLaunchConfiguration (`<unset>`): remove a launch configuration."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.actions.named_value_actions import UnsetNamedValue
from launch.frontend.expose import expose_action

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


@expose_action('unset')
class UnsetLaunchConfiguration(UnsetNamedValue):
    @staticmethod
    def entries(context: LaunchContext) -> dict[str, str]:
        return context.launch_configurations
