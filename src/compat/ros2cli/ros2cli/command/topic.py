"""`ros2 topic`: the command; its verbs are the modules of ros2cli.verb.topic.

list, info, type, find, echo, pub, hz and bw; what they share is ros2cli.api.topic.
"""

import argparse

from ros2cli.command import VerbCommand


class TopicCommand(VerbCommand):
    """Various topic related sub-commands."""

    VERB_GROUP = 'ros2topic.verb'

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the verbs, and --include-hidden-topics as an option of the command itself (as upstream).

        The list, type and find verbs honour it as they do their own --include-hidden-topics.
        """
        parser.add_argument('--include-hidden-topics', dest='command_include_hidden', action='store_true',
                            help='Consider hidden topics as well')
        super().add_arguments(parser, cli_name)
