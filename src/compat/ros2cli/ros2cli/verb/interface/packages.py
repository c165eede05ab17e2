"""`ros2 interface packages`: the packages that provide interfaces."""

import argparse

from ros2cli.api.interface import _add_kind_filters, _wanted_kinds
from ros2cli.verb import VerbExtension


class PackagesVerb(VerbExtension):
    """Output a list of packages that provide interfaces."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the -m/-s/-a filters: only packages with interfaces of that kind."""
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the packages that provide interfaces of the kinds the filters allow."""
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
        from rosidl_runtime_py.get_interfaces import interface_index
        wanted = _wanted_kinds(args)
        for package, kinds in sorted(interface_index().items()):
            if any(kinds[kind] for kind in wanted):
                print(package)
        return 0
