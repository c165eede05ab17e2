"""A command whose import fails, as one does when its package lacks a dependency."""

import a_module_that_is_not_installed  # noqa: F401
from ros2cli.command import CommandExtension


class BrokenCommand(CommandExtension):
    """Never seen: its module cannot be imported."""
