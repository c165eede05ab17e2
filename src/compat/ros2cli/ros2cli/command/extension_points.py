"""`ros2 extension_points`: upstream ros2cli's listing of the extension points.

They are the entry points of the group 'ros2cli.extension_point': a group name each, with the base
class its extensions extend.
"""

from __future__ import annotations

import argparse

from ros2cli.command import CommandExtension
from ros2cli.entry_points import get_entry_points, get_first_line_doc, load_entry_point


def extension_point_groups() -> dict[str, str]:
    """{group: first docstring line of its base class} of the group 'ros2cli.extension_point'.

    A base class that cannot be imported is warned about and listed without its description.
    """
    groups = {}
    for name, entry_point in sorted(get_entry_points('ros2cli.extension_point').items()):
        base = load_entry_point(entry_point)
        groups[name] = get_first_line_doc(base) if base is not None else ''
    return groups


class ExtensionPointsCommand(CommandExtension):
    """List extension points."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -v/--verbose (show the base class each extension point expects)."""
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='Show the class that each extension point expects')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Print each extension point's group with its base class's first docstring line."""
        bases = get_entry_points('ros2cli.extension_point')
        for group, description in extension_point_groups().items():
            detail = f' ({bases[group].value})' if args.verbose else ''
            print(f'{group}: {description}{detail}')
        return 0
