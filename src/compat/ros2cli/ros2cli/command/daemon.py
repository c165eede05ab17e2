"""`ros2 daemon`: the per-domain background process with the warm graph cache.

Its verbs (start, stop, status) are the modules of ros2cli.verb.daemon.
"""

from ros2cli.command import VerbCommand


class DaemonCommand(VerbCommand):
    """Various daemon related sub-commands."""

    VERB_GROUP = 'ros2cli.daemon.verb'
