"""LaunchLogDir: the log directory of this launch."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.logging import launch_config
from launch.substitution import Substitution
from launch.substitutions.substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchLogDir(Substitution):
    """The directory this launch writes its logs to."""

    def perform(self, context: LaunchContext) -> str:
        if launch_config.log_dir is None:
            raise SubstitutionFailure('this launch has no log directory')
        return str(launch_config.log_dir)
