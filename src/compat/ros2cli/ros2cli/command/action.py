"""`ros2 action`: the command; its verbs are the modules of ros2cli.verb.action.

They are list, info, type and send_goal (Jazzy has no `action find`; Rolling added it).
"""

from ros2cli.command import VerbCommand


class ActionCommand(VerbCommand):
    """Various action related sub-commands."""

    VERB_GROUP = 'ros2action.verb'
