"""`ros2 extensions`: upstream ros2cli's listing of the installed extensions.

It shows, extension point by extension point, which installed packages extend it.
"""

from __future__ import annotations

import argparse
import sys

from ros2cli.command import CommandExtension
from ros2cli.command.extension_points import extension_point_groups
from ros2cli.entry_points import get_entry_points, get_first_line_doc, load_entry_point


class ExtensionsCommand(CommandExtension):
    """List extensions."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -a/--all (extensions that fail to load too, with the reason) and -v/--verbose."""
        parser.add_argument('-a', '--all', action='store_true',
                            help='Also show extensions that fail to load, with the reason (instead of '
                                 'a warning line)')
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='Show the module and class of each extension')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Print each extension point's extensions with their first docstring lines, group by group."""
        for group in extension_point_groups():
            print(f'{group}:')
            for name, entry_point in sorted(get_entry_points(group).items()):
                detail = f' ({entry_point.value})' if args.verbose else ''
                if args.all:
                    try:
                        extension = entry_point.load()
                    except Exception as error:  # shown, not raised: that is what --all is for
                        reason = ' '.join(str(error).split())
                        print(f'  {name}: failed to load: {type(error).__name__}: {reason}{detail}')
                        continue
                else:
                    extension = load_entry_point(entry_point)  # a warning line if it fails
                    if extension is None:
                        continue
                print(f'  {name}: {get_first_line_doc(extension)}{detail}')
        sys.stdout.flush()
        return 0
