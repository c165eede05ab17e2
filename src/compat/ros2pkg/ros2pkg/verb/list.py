"""`ros2 pkg list`: every package on AMENT_PREFIX_PATH."""

from __future__ import annotations

import argparse

from ros2cli.verb import VerbExtension

from ros2pkg.api import get_package_names


class ListVerb(VerbExtension):
    """Output a list of available packages."""

    def main(self, *, args: argparse.Namespace) -> int:
        """List the packages: see main_list."""
        return main_list(args)


def main_list(args: argparse.Namespace) -> int:
    """Print the name of every package on AMENT_PREFIX_PATH, one a line, sorted; always 0."""
    for name in get_package_names():
        print(name)
    return 0
