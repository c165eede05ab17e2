"""`ros2 run <package> <executable> [args]` (placeholder until the CLI issue fills it in)."""

import argparse
import os

from ament_index_python.packages import PackageNotFoundError, get_package_prefix

DESCRIPTION = 'Run a package specific executable'


def add_arguments(parser: argparse.ArgumentParser, cli_name: str) -> None:
    parser.add_argument('package_name', help='Name of the ROS package')
    parser.add_argument('executable_name', help='Name of the executable')
    parser.add_argument('argv', nargs=argparse.REMAINDER, help='Pass arbitrary arguments to the executable')


def main(args: argparse.Namespace) -> int | str:
    try:
        prefix = get_package_prefix(args.package_name)
    except PackageNotFoundError:
        return 'Package not found'
    path = os.path.join(prefix, 'lib', args.package_name, args.executable_name)
    if not os.access(path, os.X_OK):
        return 'No executable found'
    os.execv(path, [path, *args.argv])
