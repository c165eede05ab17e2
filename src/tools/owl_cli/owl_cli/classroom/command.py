"""The `owl class` command and its two: `owl class serve` and `owl class image`."""

from __future__ import annotations

import argparse

from owl_cli import classroom
from owl_cli.classroom import image, serve
from owl_cli.command import Command


class ClassCommand(Command):
    """`owl class serve|image ...`."""

    help = 'a class server on JupyterHub: every student in a browser'
    description = classroom.__doc__

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Its own two commands, serve and image, with their options."""
        commands = parser.add_subparsers(dest='class_command', metavar='COMMAND', required=True)
        serve.add_arguments(commands.add_parser(
            'serve', help='start the class server for the students of a class list (as root)',
            description=serve.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter))
        image.add_arguments(commands.add_parser(
            'image', help="make this checkout a class's single-user image for Kubernetes (while building it)",
            description=image.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter))

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run `owl class serve` or `owl class image`."""
        run = {'serve': serve.run, 'image': image.run}[args.class_command]
        return run(args)
