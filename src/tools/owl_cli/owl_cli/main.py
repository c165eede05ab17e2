"""owl: Owl Kit Lab's own command (next to the course's `ros2`)."""

from __future__ import annotations

import argparse
import sys
from importlib.metadata import entry_points

from owl_cli.command import COMMAND_GROUP, Command


def commands() -> dict[str, Command]:
    """Every command of the owl_cli.command entry points, by name, in the order of their names."""
    return {entry.name: entry.load()() for entry in sorted(entry_points(group=COMMAND_GROUP),
                                                          key=lambda entry: entry.name)}


def main(argv: list[str] | None = None) -> int:
    """The `owl` command: run the sub-command argv names (None: sys.argv); its exit code, 130 at Ctrl-C."""
    parser = argparse.ArgumentParser(prog='owl', description=__doc__)
    subparsers = parser.add_subparsers(dest='command', metavar='COMMAND', required=True)
    found = commands()
    for name, command in found.items():
        command.add_arguments(subparsers.add_parser(name, help=command.help, description=command.description,
                                                    formatter_class=command.formatter_class),
                              f'{parser.prog} {name}')
    args = parser.parse_args(argv)
    try:
        return found[args.command].main(parser=subparsers.choices[args.command], args=args)
    except KeyboardInterrupt:
        return 130


if __name__ == '__main__':
    sys.exit(main())
