"""`ros2 interface`: the command; its verbs are the modules of ros2cli.verb.interface.

They are show, list, package, packages and proto, from the installed interface files.
"""

from ros2cli.command import VerbCommand


class InterfaceCommand(VerbCommand):
    """Show information about ROS interfaces."""

    VERB_GROUP = 'ros2interface.verb'
