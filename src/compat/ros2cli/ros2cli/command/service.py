"""`ros2 service`: the command; its verbs are the modules of ros2cli.verb.service.

list, type, find, info, call and echo; what they share is ros2cli.api.service.
"""

import argparse

from ros2cli.command import VerbCommand


class ServiceCommand(VerbCommand):
    """Various service related sub-commands."""

    VERB_GROUP = 'ros2service.verb'

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the verbs, and --include-hidden-services as an option of the command itself (as upstream).

        `info` honours only this one; list and find also have their own.
        """
        parser.add_argument('--include-hidden-services', dest='command_include_hidden', action='store_true',
                            help='Consider hidden services as well')
        super().add_arguments(parser, cli_name)
