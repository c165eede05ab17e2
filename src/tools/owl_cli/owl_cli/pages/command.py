"""`owl pages`: the front door's address and every page of the kit, running or not.

Starts the front door when none runs (it stays, like ros2's daemon, until `owl pages --stop`), so
its index is there to open even before any page runs. A page that does not run shows the command
that starts it.
"""

from __future__ import annotations

import argparse
import sys

from olive_kit.description import page_catalogue
from owl_web import pages
from owl_web.origins import TrustedOrigins

from owl_cli.command import Command


def table(states: list[pages.PageState], front_door: str | None) -> str:
    """The pages as aligned columns: name, state, address to open, and its own address or how to start it."""
    rows = [('PAGE', 'STATE', 'OPEN', 'OWN ADDRESS, OR HOW TO START IT')]
    for state in states:
        page = state.page
        module = f' (module {page.address})' if page.address else ''
        if state.running:
            where = f'{front_door}{page.mount}/' if front_door else page.url
            rows.append((page.title, 'running', where, f'{page.url}{module}'))
        else:
            rows.append((page.title, 'not running', '-', f'{page.start}{module}'))
    widths = [max(len(row[i]) for row in rows) for i in range(3)]
    return '\n'.join('  '.join([*(cell.ljust(width) for cell, width in zip(row, widths, strict=False)),
                                row[3]]).rstrip() for row in rows)


def run(args: argparse.Namespace) -> int:
    """Run `owl pages`: exit code 0, or 1 with one line when the front door cannot start."""
    folder = pages.pages_dir()
    try:
        if args.stop:
            stopped = pages.stop_front_door(folder)
            print('owl pages: the front door stopped' if stopped else 'owl pages: no front door runs')
            return 0
        TrustedOrigins.from_environment()  # a malformed OWL_TRUSTED_ORIGINS is said here, not in its log
        pages.write_catalogue([pages.Page.from_json(entry) for entry in page_catalogue()], folder)
        front_door = pages.ensure_front_door(folder) if pages.front_door_wanted() else None
    except (pages.PagesError, ValueError, OSError) as error:
        print(f'owl pages: {error}')
        return 1
    if front_door:
        print(f'owl pages: the front door: {front_door} (every running page is there; Ctrl-C does not stop '
              "it: 'owl pages --stop')")
    else:
        print('owl pages: no front door (OWL_FRONT_DOOR=off): each page is at its own address')
    print(table(pages.page_states(folder), front_door))
    return 0


class PagesCommand(Command):
    """`owl pages [--stop]`."""

    help = 'the front door (one address for every page) and every page, running or not'
    description = sys.modules[__name__].__doc__  # the module's (in here __doc__ is the class's)
    formatter_class = argparse.RawDescriptionHelpFormatter

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """`owl pages`' option, --stop."""
        parser.add_argument('--stop', action='store_true',
                            help='stop the front door (the pages keep their own addresses)')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run `owl pages`."""
        return run(args)
