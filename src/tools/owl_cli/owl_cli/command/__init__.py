"""What an `owl` command is: a class named in the `owl_cli.command` entry-point group.

Like ros2cli's command extensions, each command is found through its package's metadata, so
another package adds an `owl` command by naming its class in its own setup.py:

    entry_points={'owl_cli.command': ['mine = my_package.command:MyCommand']}

owl_cli.main makes the command's parser from help, description and formatter_class, has
add_arguments() fill it, and runs main() with what was parsed.
"""

from __future__ import annotations

import argparse

COMMAND_GROUP = 'owl_cli.command'


class Command:
    """One `owl` command (`owl NAME ...`), its name the entry point's."""

    help = ''  # its line in `owl -h`
    description: str | None = None  # `owl NAME -h`'s text above the options
    formatter_class: type[argparse.HelpFormatter] = argparse.HelpFormatter

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the command's arguments to its parser; cli_name is how it is called, e.g. 'owl check'."""

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run the command with the parsed arguments (parser: its own, for parser.error); its exit code."""
        raise NotImplementedError(f'{type(self).__name__} has no main()')
