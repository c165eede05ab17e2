"""`ros2 run [--prefix PREFIX] <package> <executable> [args]`: run a package's executable.

The work is ros2cli.api.run's (upstream's ros2run.api): see run() there.
"""

import argparse

from ros2cli.command import CommandExtension


class RunCommand(CommandExtension):
    """Run a package specific executable."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add run's options (see add_run_arguments)."""
        add_run_arguments(parser)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str:
        """Run the executable (see ros2cli.api.run.run); its exit code, or the error message."""
        # Lazy: `ros2 -h` imports every command module; ros2cli.api.run imports subprocess.
        from ros2cli.api.run import run
        return run(args)


def add_run_arguments(parser: argparse.ArgumentParser) -> None:
    """Add --prefix, the package name, the executable name (both completed in the shell) and its arguments."""
    # Lazy: `ros2 -h` imports every command module, and needs neither these nor their imports.
    from ros2cli.api.run import executable_completer
    from ros2cli.completion import package_completer, with_completer

    parser.add_argument('--prefix', help='Prefix command, which should go before the executable. '
                                         'Command must be wrapped in quotes if it contains spaces '
                                         "(e.g. --prefix 'gdb -ex run --args').")
    with_completer(parser.add_argument('package_name', help='Name of the ROS package'), package_completer)
    with_completer(parser.add_argument('executable_name', help='Name of the executable'),
                   executable_completer)
    parser.add_argument('argv', nargs=argparse.REMAINDER, help='Pass arbitrary arguments to the executable')
