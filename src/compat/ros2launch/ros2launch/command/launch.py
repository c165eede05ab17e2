"""`ros2 launch [options] <package_name> <launch_file_name> [name:=value ...]` or `<path>`.

`ros2` finds the command through this package's entry point ('ros2cli.command' in setup.py).
"""

from __future__ import annotations

import argparse
import os
import sys

from ros2cli.command import CommandExtension


class LaunchCommand(CommandExtension):
    """Run a launch file."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the launch options (see add_launch_arguments)."""
        add_launch_arguments(parser)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str:
        """Launch the file, or show it (-p) or its arguments (-s); the exit code (see launch())."""
        return launch(args)


def add_launch_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the options, the package name (or a path), the launch file name and the name:=value arguments."""
    parser.add_argument('-n', '--noninteractive', action='store_true', default=not sys.stdin.isatty(),
                        help='Run the launch system non-interactively, with no terminal associated')
    parser.add_argument('-d', '--debug', action='store_true',
                        help='Put the launch system in debug mode, provides more verbose output.')
    command = parser.add_mutually_exclusive_group()
    command.add_argument('-p', '--print', '--print-description', action='store_true',
                         help='Print the launch description to the console without launching it.')
    command.add_argument('-s', '--show-args', '--show-arguments', action='store_true',
                         help='Show arguments that may be given to the launch file.')
    parser.add_argument('-a', '--show-all-subprocesses-output', action='store_true',
                        help='Show all launched subprocesses\' output by overriding their output '
                             'configuration using the OVERRIDE_LAUNCH_PROCESS_OUTPUT envvar.')
    parser.add_argument('--launch-prefix',
                        help='Prefix command, which should go before all executables. Command must '
                             'be wrapped in quotes if it contains spaces (e.g. --launch-prefix '
                             '"xterm -e").')
    parser.add_argument('--launch-prefix-filter',
                        help='Regex pattern for filtering which executables the --launch-prefix is '
                             'applied to by matching the executable name.')
    parser.add_argument('package_name', help='Name of the ROS package which contains the launch file, '
                        'or the path to a launch file')
    parser.add_argument('launch_file_name', nargs='?',
                        help='Name of the launch file (or the first launch argument with a path)')
    parser.add_argument('launch_arguments', nargs='*', default=[],
                        help="Arguments to the launch file; '<name>:=<value>' (for duplicates, last "
                             'one wins)')


def resolve_launch_file(args: argparse.Namespace) -> tuple[str, list[str]]:
    """(path of the launch file, the name:=value arguments) from the positionals."""
    # Lazy: ros2launch.api imports `launch`, which takes a while, and `ros2 -h` imports this module.
    from ros2launch.api import get_share_file_path_from_package

    arguments = list(args.launch_arguments)
    if os.path.isfile(args.package_name):
        if args.launch_file_name is not None:
            arguments.insert(0, args.launch_file_name)
        return os.path.abspath(args.package_name), arguments
    if args.launch_file_name is None:
        raise RuntimeError(f"no launch file '{args.package_name}' found; to run a launch file of a "
                           'package: ros2 launch <package_name> <launch_file_name>')
    return get_share_file_path_from_package(args.package_name, args.launch_file_name), arguments


def launch(args: argparse.Namespace) -> int | str:
    """Run `ros2 launch` with the parsed arguments; launch's exit code, or 0 after -p or -s.

    A missing package or file or a malformed name:=value raises RuntimeError, and so does a broken
    launch file for -p and -s; --launch-prefix-filter without --launch-prefix is the error message.
    """
    # Lazy: ros2launch.api imports `launch`, which takes a while, and `ros2 -h` imports this module.
    from ros2launch.api import (
        format_arguments_of_launch_file,
        format_launch_description,
        launch_a_launch_file,
        parse_launch_arguments,
    )

    if args.launch_prefix_filter is not None and args.launch_prefix is None:
        return "'--launch-prefix-filter' must be used together with '--launch-prefix'"
    path, raw_arguments = resolve_launch_file(args)
    launch_arguments = parse_launch_arguments(raw_arguments)
    if args.launch_prefix is not None:
        launch_arguments.append(('launch-prefix', args.launch_prefix))
    if args.launch_prefix_filter is not None:
        launch_arguments.append(('launch-prefix-filter', args.launch_prefix_filter))
    if args.show_all_subprocesses_output:
        os.environ['OVERRIDE_LAUNCH_PROCESS_OUTPUT'] = 'both'
    if args.show_args:
        print(format_arguments_of_launch_file(path))
        return 0
    if args.print:
        print(format_launch_description(path))
        return 0
    return launch_a_launch_file(path, launch_arguments, noninteractive=args.noninteractive,
                                debug=args.debug, argv=raw_arguments)
