"""`ros2 extension_points` and `ros2 extensions`: upstream ros2cli's two introspection commands.

They show which extension points there are, and which installed packages extend them.
"""

from __future__ import annotations

import argparse
import sys

from ros2cli.command import CommandExtension


def _extension_point_groups() -> dict[str, str]:
    """{group: first docstring line of its base class} of the group 'ros2cli.extension_point'.

    A base class that cannot be imported is warned about and listed without its description.
    """
    from ros2cli.entry_points import get_entry_points, get_first_line_doc, load_entry_point
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
        from ros2cli.entry_points import get_entry_points
        bases = get_entry_points('ros2cli.extension_point')
        for group, description in _extension_point_groups().items():
            detail = f' ({bases[group].value})' if args.verbose else ''
            print(f'{group}: {description}{detail}')
        return 0


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
        from ros2cli.entry_points import get_entry_points, get_first_line_doc, load_entry_point
        for group in _extension_point_groups():
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
