"""`ros2 interface list`: every installed interface, by kind."""

import argparse

from ros2cli.api.interface import _add_kind_filters, _wanted_kinds
from ros2cli.verb import VerbExtension

SECTION_TITLES = (('msg', 'Messages:'), ('srv', 'Services:'), ('action', 'Actions:'))


class ListVerb(VerbExtension):
    """List all interface types available."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the -m/-s/-a filters (only messages, services or actions)."""
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print every installed interface's full name, in a section per kind the filters allow."""
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
        from rosidl_runtime_py.get_interfaces import interface_index
        index = interface_index()
        wanted = _wanted_kinds(args)
        for kind, title in SECTION_TITLES:
            if kind in wanted:
                print(title)
                for package in sorted(index):
                    for name in index[package][kind]:
                        print(f'    {package}/{kind}/{name}')
        return 0
