"""`ros2 service`: the command; its verbs (list, type, find, call) are the modules of ros2cli.verb.service."""

from ros2cli.command import VerbCommand


class ServiceCommand(VerbCommand):
    """Various service related sub-commands."""

    VERB_GROUP = 'ros2service.verb'
