"""`ros2 bag`: the command; its verbs are the modules of ros2bag.verb."""

from ros2cli.command import VerbCommand


class BagCommand(VerbCommand):
    """Various rosbag related sub-commands."""

    VERB_GROUP = 'ros2bag.verb'
