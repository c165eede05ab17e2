"""`ros2 pkg prefix`: a package's install prefix or share directory."""

from __future__ import annotations

import argparse

from ros2cli.verb import VerbExtension

from ros2pkg.api import PACKAGE_NOT_FOUND, _package_argument, get_prefix_path, get_share_directory


class PrefixVerb(VerbExtension):
    """Output the prefix path of a package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and --share."""
        _package_argument(parser)
        parser.add_argument('--share', action='store_true', help='Show share directory for the package')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the package's prefix: see main_prefix."""
        return main_prefix(args)


def main_prefix(args: argparse.Namespace) -> int | str:
    """Print a package's install prefix, or its share directory with --share; PACKAGE_NOT_FOUND if missing."""
    lookup = get_share_directory if args.share else get_prefix_path
    path = lookup(args.package_name)
    if path is None:
        return PACKAGE_NOT_FOUND
    print(path)
    return 0
