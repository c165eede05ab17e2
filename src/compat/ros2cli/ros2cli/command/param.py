"""`ros2 param`: the command; its verbs are the modules of ros2cli.verb.param.

They are list, get, set, delete, describe, dump and load, through the nodes' parameter services
(ros2cli.api.param).
"""

from ros2cli.command import VerbCommand


class ParamCommand(VerbCommand):
    """Various param related sub-commands."""

    VERB_GROUP = 'ros2param.verb'
