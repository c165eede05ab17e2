"""`ros2 interface package`: the interfaces of one package."""

import argparse

from ros2cli.api.interface import _add_kind_filters, _unknown_package, _wanted_kinds
from ros2cli.completion import package_completer, with_completer
from ros2cli.verb import VerbExtension


class PackageVerb(VerbExtension):
    """Output a list of available interface types within one package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and the -m/-s/-a filters."""
        with_completer(parser.add_argument('package_name', help='Name of the ROS package'), package_completer)
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the package's interfaces as full names; the error message for an unknown package."""
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
        from rosidl_runtime_py.get_interfaces import interface_index
        index = interface_index()
        if args.package_name not in index:
            return _unknown_package(args.package_name)
        for kind in _wanted_kinds(args):
            for name in index[args.package_name][kind]:
                print(f'{args.package_name}/{kind}/{name}')
        return 0
