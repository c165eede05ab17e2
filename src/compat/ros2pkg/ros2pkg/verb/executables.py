"""`ros2 pkg executables`: the executables of one package, or of every package."""

from __future__ import annotations

import argparse
import os

from ros2cli.verb import VerbExtension

from ros2pkg.api import PackageNotFound, _package_argument, get_executable_paths, get_package_names


class ExecutablesVerb(VerbExtension):
    """Output a list of package specific executables."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add an optional package name (none: every package) and --full-path."""
        _package_argument(parser, nargs='?')
        parser.add_argument('--full-path', action='store_true', default=False,
                            help='Show full path of each executable')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """List the executables: see main_executables."""
        return main_executables(args)


def main_executables(args: argparse.Namespace) -> int | str:
    """Print '<package> <executable>' (or the full path) for one package's executables, or every package's.

    Returns an error message for a package that is not found.
    """
    names = [args.package_name] if args.package_name else get_package_names()
    for name in names:
        try:
            paths = get_executable_paths(name)
        except PackageNotFound:
            return f"Package '{name}' not found"
        for path in paths:
            print(path if args.full_path else f'{name} {os.path.basename(path)}')
    return 0
