"""ThisLaunchFileDir: the directory of the launch file being loaded."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class ThisLaunchFileDir(Substitution):
    """The directory of the launch file being loaded."""

    def perform(self, context: LaunchContext) -> str:
        try:
            return context.locals.current_launch_file_directory
        except AttributeError:
            raise SubstitutionFailure(
                'ThisLaunchFileDir used outside of a launch file (in a script)') from None

    def describe(self) -> str:
        return 'ThisLaunchFileDir()'
