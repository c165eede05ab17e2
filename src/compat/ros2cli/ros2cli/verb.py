"""Verbs of a command: `ros2 <command> <verb> ...`, each a small class registered in a table."""

import argparse
from typing import Any


class Verb:
    """One verb: DESCRIPTION, add_arguments() and main(args) -> int | str | None (see cli.py)."""

    DESCRIPTION = ''

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        pass

    def main(self, args: argparse.Namespace) -> Any:
        raise NotImplementedError


def add_command_subparsers(parser: argparse.ArgumentParser, cli_name: str, summaries: dict[str, str],
                           dest: str) -> Any:
    """Sub-parsers listed as upstream lists them: one padded line per name, then the hint line."""
    width = max(map(len, summaries), default=0) + 2
    listing = '\n'.join(f'{name:<{width}}{summary}' for name, summary in sorted(summaries.items()))
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    return parser.add_subparsers(title='Commands', description=listing, dest=dest,
                                 metavar=f'Call `{cli_name} <command> -h` for more detailed usage.')


def add_verbs(parser: argparse.ArgumentParser, cli_name: str, verbs: dict[str, type[Verb]]) -> None:
    """Add a sub-parser per verb; `ros2 <command>` alone prints the command's help."""
    subparsers = add_command_subparsers(
        parser, cli_name, {name: verb.DESCRIPTION for name, verb in verbs.items()}, '_verb_name')
    for name, verb_class in verbs.items():
        verb = verb_class()
        verb_parser = subparsers.add_parser(
            name, description=verb.DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
        verb.add_arguments(verb_parser, f'{cli_name} {name}')
        verb_parser.set_defaults(_verb=verb)
    parser.set_defaults(_verb=None)


def run_verb(args: argparse.Namespace) -> Any:
    """The command's main: run the chosen verb, or print the command's help."""
    if args._verb is None:
        args._parser.print_help()
        return 0
    return args._verb.main(args)
