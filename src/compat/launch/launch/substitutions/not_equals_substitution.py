"""NotEqualsSubstitution: whether two values differ."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.substitutions.equals_substitution import EqualsSubstitution

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class NotEqualsSubstitution(EqualsSubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(super().perform(context) == 'false').lower()
