"""`ros2 pkg`: the command; its verbs are the modules of ros2pkg.verb.

`ros2` finds them through this package's entry points ('ros2cli.command' and 'ros2pkg.verb' in
setup.py). This module imports nothing else: `ros2 -h` imports it for its docstring.
"""

from ros2cli.command import VerbCommand


class PkgCommand(VerbCommand):
    """Various package related sub-commands."""

    VERB_GROUP = 'ros2pkg.verb'
