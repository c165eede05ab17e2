"""`ros2 run [--prefix PREFIX] <package> <executable> [args]`: run a package's executable.

Arguments go through untouched; the child gets its own process group (and the terminal, when
there is one) so that every SIGINT/SIGTERM reaches it exactly once, whether it came from the
terminal, from `kill <pid of ros2>` or from a signal to the whole group of `ros2`.
"""

import argparse
import os
import signal
import sys

from ros2cli.command import CommandExtension

FORWARDED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


class RunCommand(CommandExtension):
    """Run a package specific executable."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add run's options (see add_run_arguments)."""
        add_run_arguments(parser)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str:
        """Run the executable (see run()); its exit code, or the error message."""
        return run(args)


def add_run_arguments(parser: argparse.ArgumentParser) -> None:
    """Add --prefix, the package name, the executable name (both completed in the shell) and its arguments."""
    from ros2cli.completion import executable_completer, package_completer, with_completer

    parser.add_argument('--prefix', help='Prefix command, which should go before the executable. '
                                         'Command must be wrapped in quotes if it contains spaces '
                                         "(e.g. --prefix 'gdb -ex run --args').")
    with_completer(parser.add_argument('package_name', help='Name of the ROS package'), package_completer)
    with_completer(parser.add_argument('executable_name', help='Name of the executable'),
                   executable_completer)
    parser.add_argument('argv', nargs=argparse.REMAINDER, help='Pass arbitrary arguments to the executable')


def package_executables(prefix: str, package: str) -> list[str]:
    """Executable files under <prefix>/lib/<package>/, recursively, hidden directories skipped."""
    found = []
    for root, dirs, files in os.walk(os.path.join(prefix, 'lib', package)):
        dirs[:] = sorted(d for d in dirs if not d.startswith('.'))
        for name in sorted(files):
            path = os.path.join(root, name)
            if os.access(path, os.X_OK) and os.path.isfile(path):
                found.append(path)
    return found


def _child_setup(take_terminal: bool) -> None:
    os.setpgid(0, 0)
    if take_terminal:
        signal.signal(signal.SIGTTOU, signal.SIG_IGN)
        os.tcsetpgrp(0, os.getpgrp())
        signal.signal(signal.SIGTTOU, signal.SIG_DFL)
    try:  # the child follows `ros2 run` when that is killed outright
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def run_executable(command: list[str]) -> int:
    """Run command with signals forwarded; its exit code (128 + N when killed by signal N).

    RuntimeError when the command cannot be started at all.
    """
    import subprocess  # here: `ros2 -h` imports this module for its docstring

    take_terminal = False
    try:
        take_terminal = os.isatty(0) and os.tcgetpgrp(0) == os.getpgrp()
    except OSError:
        pass
    try:
        process = subprocess.Popen(command, preexec_fn=lambda: _child_setup(take_terminal))
    except OSError as error:
        raise RuntimeError(f"Cannot run '{command[0]}': {error.strerror}") from None

    def forward(signum: int, _frame: object) -> None:
        try:
            os.kill(process.pid, signum)
        except ProcessLookupError:
            pass

    for signum in FORWARDED_SIGNALS:
        signal.signal(signum, forward)
    try:
        code = process.wait()
    finally:
        if take_terminal:
            signal.signal(signal.SIGTTOU, signal.SIG_IGN)
            try:
                os.tcsetpgrp(0, os.getpgrp())
            except OSError:
                pass
            signal.signal(signal.SIGTTOU, signal.SIG_DFL)
    if code < 0:
        print(f'[ros2run]: {signal.strsignal(-code) or f"Signal {-code}"}')
        return 128 - code
    if code:
        print(f'[ros2run]: Process exited with failure {code}')
    return code


def run(args: argparse.Namespace) -> int | str:
    """Run the package's executable with the given arguments; its exit code or the error message.

    An unknown package or executable gives the error message with a 'did you mean' hint and, for an
    executable, the package's executables. --prefix (shell words) goes in front of the command.
    """
    from ament_index_python.packages import (
        PackageNotFoundError,
        get_package_prefix,
        get_packages_with_prefixes,
    )
    from owl_common.hints import did_you_mean

    try:
        prefix = get_package_prefix(args.package_name)
    except (PackageNotFoundError, ValueError):
        hint = did_you_mean(args.package_name, get_packages_with_prefixes())
        return f"Package '{args.package_name}' not found{hint}"
    executables = package_executables(prefix, args.package_name)
    matches = [path for path in executables if os.path.basename(path) == args.executable_name]
    if not matches:
        names = sorted({os.path.basename(path) for path in executables})
        if not names:
            return f"No executable found: package '{args.package_name}' has no executables"
        hint = did_you_mean(args.executable_name, names)
        return (f"No executable found: package '{args.package_name}' has no executable "
                f"'{args.executable_name}'{hint}; its executables: {', '.join(names)}")
    if len(matches) > 1:
        return 'Multiple executables found:' + ''.join(f'\n- {path}' for path in matches)
    command = [matches[0], *args.argv]
    if args.prefix:
        import shlex
        command = [*shlex.split(args.prefix), *command]
    sys.stdout.flush()
    return run_executable(command)
