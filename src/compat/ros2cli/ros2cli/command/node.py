"""`ros2 node`: the command; its verbs (list, info) are the modules of ros2cli.verb.node."""

from ros2cli.command import VerbCommand


class NodeCommand(VerbCommand):
    """Various node related sub-commands."""

    VERB_GROUP = 'ros2node.verb'
