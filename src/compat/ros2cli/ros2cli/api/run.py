"""What `ros2 run` does: find a package's executable and run it with its signals forwarded.

Arguments go through untouched; the child gets its own process group (and the terminal, when
there is one) so that every SIGINT/SIGTERM reaches it exactly once, whether it came from the
terminal, from `kill <pid of ros2>` or from a signal to the whole group of `ros2`.
"""

import argparse
import os
import shlex
import signal
import subprocess
import sys
from collections.abc import Iterable

from ament_index_python.packages import (
    PackageNotFoundError,
    get_package_prefix,
    get_packages_with_prefixes,
)
from owl_common.hints import did_you_mean

FORWARDED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


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


def executable_completer(prefix: str, parsed_args: argparse.Namespace, **_kwargs: object) -> Iterable[str]:
    """The package's executable names that start with prefix, sorted (none for an unknown package).

    The package is the one given before it on the command line (parsed_args.package_name).
    """
    try:
        package_prefix = get_package_prefix(parsed_args.package_name)
    except Exception:
        return []
    names = {os.path.basename(p) for p in package_executables(package_prefix, parsed_args.package_name)}
    return sorted(n for n in names if n.startswith(prefix))


def _child_setup(take_terminal: bool) -> None:
    os.setpgid(0, 0)
    if take_terminal:
        signal.signal(signal.SIGTTOU, signal.SIG_IGN)
        os.tcsetpgrp(0, os.getpgrp())
        signal.signal(signal.SIGTTOU, signal.SIG_DFL)
    try:  # the child follows `ros2 run` when that is killed outright
        import ctypes  # lazy: only the child needs it, and `ros2 run -h` (completion too) imports this module
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def run_executable(command: list[str]) -> int:
    """Run command with signals forwarded; its exit code (128 + N when killed by signal N).

    RuntimeError when the command cannot be started at all.
    """
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
        command = [*shlex.split(args.prefix), *command]
    sys.stdout.flush()
    return run_executable(command)
