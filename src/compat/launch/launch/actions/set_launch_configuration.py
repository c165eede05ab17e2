"""SetLaunchConfiguration (`<let>`): set a launch configuration."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.actions.named_value_actions import SetNamedValue
from launch.frontend.expose import expose_action
from launch.substitution import describe_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


@expose_action('let')
class SetLaunchConfiguration(SetNamedValue):
    @staticmethod
    def entries(context: LaunchContext) -> dict[str, str]:
        return context.launch_configurations

    def describe(self) -> str:
        return (f'SetLaunchConfiguration({describe_substitutions(self.name)} = '
                f'{describe_substitutions(self.value)})')
