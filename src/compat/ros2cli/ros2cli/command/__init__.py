"""`ros2 <command>`: the command extension point (entry point group 'ros2cli.command').

A command is a class with a docstring (its first line is what `ros2 -h` lists),
    add_arguments(self, parser, cli_name) -> None    its options, and its verbs if it has any
    main(self, *, parser, args) -> int | str | None  its work (see ros2cli.cli for the result)
registered under its name in the group 'ros2cli.command' of its package's entry points. A command
with verbs calls add_subparsers_on_demand(parser, cli_name, '_verb', '<package>.verb') in
add_arguments and runs `args._verb.main(args=args)` (see VerbCommand, which does both).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ros2cli.entry_points import get_entry_points, get_first_line_doc
from ros2cli.plugin_system import PLUGIN_SYSTEM_VERSION, instantiate_extensions, satisfies_version

# The words `ros2` was called with (set by ros2cli.cli.main; sys.argv[1:] otherwise): which command
# and verb they choose decides which extensions are imported at all.
ARGV: list[str] | None = None


class CommandExtension:
    """The extension point for `ros2` commands (the base class of a command)."""

    NAME: str | None = None
    EXTENSION_POINT_VERSION = '0.1'

    def __init__(self) -> None:
        satisfies_version(PLUGIN_SYSTEM_VERSION, '^0.1')

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the command's options (and verbs) to its parser; by default it has none."""
        pass

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str | None:
        """Do the command's work; every command must override it (see ros2cli.cli for the result)."""
        raise NotImplementedError


def get_command_extensions(group_name: str) -> dict[str, Any]:
    """Every extension of a group, instantiated (upstream's name; loads all of them)."""
    return instantiate_extensions(group_name)


def _chosen_name(cli_name: str, argv: list[str] | None) -> str | None:
    """The word at this parser's depth ('ros2' 0, 'ros2 topic' 1): the extension the user chose.

    Option values are not told apart from words here; a wrong guess only means every extension of
    the group is loaded, as for `-h`.
    """
    given = argv if argv is not None else ARGV if ARGV is not None else sys.argv[1:]
    words = [word for word in given if not word.startswith('-')]
    depth = len(cli_name.split()) - 1
    return words[depth] if len(words) > depth else None


def add_subparsers(parser: argparse.ArgumentParser, cli_name: str, dest: str,
                   extensions: dict[str, Any], hide_extensions: list[str] | None = None,
                   required: bool = True, names: list[str] | None = None,
                   with_arguments: bool = True) -> Any:
    """A sub-parser per extension; the chosen one sets `args.<dest>` to the extension.

    They are listed as upstream lists them (one padded line each, then the hint line). `names`
    adds bare sub-parsers for extensions that were not loaded (so that their names still parse).
    Without `with_arguments` the extensions' add_arguments() is not called: a listing needs none.
    """
    shown = {name: extension for name, extension in extensions.items() if name not in (hide_extensions or ())}
    width = max(map(len, shown), default=0) + 2
    listing = '\n'.join(f'{name:<{width}}{get_first_line_doc(extension)}'
                        for name, extension in sorted(shown.items()))
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    subparsers = parser.add_subparsers(title='Commands', description=listing or None,
                                       metavar=f'Call `{cli_name} <command> -h` for more detailed usage.')
    subparsers.required = required
    for name in sorted({*extensions, *(names or ())}):
        extension = extensions.get(name)
        if extension is None:
            subparsers.add_parser(name)
            continue
        command_parser = subparsers.add_parser(name, description=get_first_line_doc(extension),
                                               formatter_class=argparse.RawDescriptionHelpFormatter)
        command_parser.set_defaults(**{dest: extension})
        if with_arguments and hasattr(extension, 'add_arguments'):
            extension.add_arguments(command_parser, f'{cli_name} {name}')
    return subparsers


def add_subparsers_on_demand(parser: argparse.ArgumentParser, cli_name: str, dest: str, group_name: str,
                             hide_extensions: list[str] | None = None, required: bool = True,
                             argv: list[str] | None = None) -> Any:
    """add_subparsers() for a group's entry points, importing only the extension that argv chooses.

    All of them are imported when argv chooses none (help) or an unknown name (the error lists
    the known ones), then without their arguments: `ros2 -h` needs the commands' docstrings, not
    their verbs.
    """
    names = sorted(get_entry_points(group_name))
    chosen = _chosen_name(cli_name, argv)
    wanted = [chosen] if chosen in names else None
    extensions = instantiate_extensions(group_name, names=wanted)
    # A broken extension was warned about and is left out of the choices.
    others = [name for name in names if name != chosen] if wanted else None
    return add_subparsers(parser, cli_name, dest, extensions, hide_extensions, required, names=others,
                          with_arguments=wanted is not None)


class VerbCommand(CommandExtension):
    """A command whose work is done by the verbs of the entry point group VERB_GROUP."""

    VERB_GROUP = ''

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add a sub-parser per verb of VERB_GROUP (only the chosen verb is imported)."""
        self._subparser = parser
        add_subparsers_on_demand(parser, cli_name, '_verb', self.VERB_GROUP, required=False)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str | None:
        """Run the chosen verb and return its result; without a verb, print the command's help."""
        if not hasattr(args, '_verb'):
            self._subparser.print_help()
            return 0
        return args._verb.main(args=args)
