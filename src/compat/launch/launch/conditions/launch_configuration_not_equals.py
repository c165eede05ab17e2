"""LaunchConfigurationNotEquals: an action executes unless a launch configuration has a given value."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.conditions.launch_configuration_equals import LaunchConfigurationEquals

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    def _equals(self, context: LaunchContext) -> bool:
        return not super()._equals(context)
