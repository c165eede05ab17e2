"""SetROSLogDir: where the ROS nodes started after it (in scope) write their logs."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


def _current_log_dir() -> Path:
    """Where ROS nodes log now: $ROS_LOG_DIR, else rcl's default $ROS_HOME/log, else ~/.ros/log."""
    if os.environ.get('ROS_LOG_DIR'):
        return Path(os.path.expanduser(os.environ['ROS_LOG_DIR']))
    if os.environ.get('ROS_HOME'):
        return Path(os.path.expanduser(os.environ['ROS_HOME'])) / 'log'
    return Path.home() / '.ros' / 'log'


@expose_action('set_ros_log_dir')
class SetROSLogDir(Action):
    """Set ROS_LOG_DIR in launch's environment.  Scoped by a GroupAction.

    A relative new_log_dir goes below the current one ($ROS_LOG_DIR, else rcl's default $ROS_HOME/log
    or ~/.ros/log); an absolute one replaces it.
    """

    def __init__(self, new_log_dir: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.log_dir = normalize_to_list_of_substitutions(new_log_dir)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_ros_log_dir> tag's new_log_dir attribute."""
        return cls, {'new_log_dir': parser.substitutions(entity.get_attr('new_log_dir'))}

    def execute(self, context: LaunchContext) -> None:
        """Set ROS_LOG_DIR for the processes started after it; ValueError for an empty directory."""
        new_log_dir = perform_substitutions(context, self.log_dir)
        if not new_log_dir:
            raise ValueError('SetROSLogDir needs a directory, got an empty one')
        # An absolute new_log_dir replaces the current one: os.path.join drops what comes before it.
        context.environment['ROS_LOG_DIR'] = os.path.join(str(_current_log_dir()), new_log_dir)
