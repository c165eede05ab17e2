"""`ros2`: parse `ros2 <command> ...` with argparse and hand over to the command's extension.

Commands and their verbs are found through entry points (see ros2cli.entry_points), so any
installed package can add one. A command's or verb's main() returns None/0 (exit 0), an int
(that exit code) or a string (printed on stderr, exit 1); a RuntimeError's message is printed
the same way. Ctrl-C exits with 2 (the value of SIGINT), as upstream. Any other exception is a
bug or a problem of the environment: it is reported in one line, never as a traceback
(ROS2CLI_TRACEBACK=1 shows it for debugging). A clean-up that hangs (a Fast DDS teardown
deadlock) ends the process after 5 s with every thread's stack and exit code 1
(owl_common.run.begin_cleanup). The `ros2` executable is console_main(), which also skips the C++
clean-up at exit (see there).
"""

import argparse
import atexit
import io
import os
import re
import shlex
import signal
import sys
import threading
import warnings
from collections.abc import Callable
from typing import NoReturn, cast

import ros2cli.command
from ros2cli.command import add_subparsers_on_demand


def build_parser(argv: list[str]) -> argparse.ArgumentParser:
    """The `ros2` parser, with the commands of the entry point group 'ros2cli.command'.

    Only the command argv chooses is imported (all of them for `ros2 -h`, whose listing needs
    their docstrings).
    """
    parser = argparse.ArgumentParser(
        prog='ros2', description='ros2 is an extensible command-line tool for ROS 2.',
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(
        '--use-python-default-buffering', action='store_true',
        help='Do not force line buffering in stdout and instead use the python default buffering, '
             'which might be affected by PYTHONUNBUFFERED/-u and depends on whatever stdout is '
             'interactive or not')
    ros2cli.command.ARGV = argv
    add_subparsers_on_demand(parser, 'ros2', '_command', 'ros2cli.command', required=False, argv=argv)
    return parser


def one_line(message: str) -> str:
    """An exception message on one line, as `ros2` reports an unexpected error.

    rcl's multi-line name errors (text, the name, a caret line) are joined, and the C source
    location rcl appends is dropped.
    """
    parts = [line.strip() for line in message.splitlines() if line.strip() and set(line.strip()) != {'^'}]
    return re.sub(r', at \S+\.c:\d+', '', ' '.join(parts))


def _completion_argv() -> list[str] | None:
    """The words being completed, when argcomplete drives this process (shell completion)."""
    if '_ARGCOMPLETE' not in os.environ:
        return None
    line = os.environ.get('COMP_LINE', '')[:int(os.environ.get('COMP_POINT', '0') or 0)]
    try:
        return shlex.split(line)[1:]
    except ValueError:
        return line.split()[1:]


def run_command(command_main: Callable[[argparse.Namespace], int | str | None],
                args: argparse.Namespace) -> int | str | None:
    """command_main(args), after which whatever ROS state it left is under the clean-up watchdog.

    A command cut short (Ctrl-C during discovery, an error) leaves its node to interpreter exit,
    where a Fast DDS teardown deadlock would otherwise hang the process; owl_common's watchdog
    ends it instead.
    """
    try:
        return command_main(args)
    finally:
        # Armed while the exception still holds the command's frames (and node); only a command
        # that imported rclpy can have a participant.
        if 'rclpy' in sys.modules:
            from owl_common.run import begin_cleanup  # lazy: it imports rclpy (loaded by now, see above)
            begin_cleanup()


def main(argv: list[str] | None = None) -> int:
    """Run `ros2` with argv (default: sys.argv[1:]) and return the process's exit code.

    A command's string result or RuntimeError is printed on stderr (exit code 1); under shell
    completion argcomplete prints the candidates and exits. The module docstring has the rest.
    """
    completing = _completion_argv()
    argv = completing if completing is not None else sys.argv[1:] if argv is None else argv
    parser = build_parser(argv)
    if completing is not None:
        import argcomplete  # lazy: only shell completion needs it, and `ros2 -h` must start fast
        argcomplete.autocomplete(parser)  # prints the candidates and exits
    args = parser.parse_args(argv)
    if not args.use_python_default_buffering:
        # typeshed types sys.stdout as TextIO; at run time it is a TextIOWrapper
        cast(io.TextIOWrapper, sys.stdout).reconfigure(line_buffering=True)
    extension = getattr(args, '_command', None)
    if extension is None:
        parser.print_help()
        return 0
    # rclpy warns while it cleans up after a failed construction; the error itself is reported.
    warnings.filterwarnings('ignore', category=RuntimeWarning, module=r'rclpy(\.|$)')
    try:
        result = run_command(lambda parsed: extension.main(parser=parser, args=parsed), args)
    except KeyboardInterrupt:
        return signal.SIGINT
    except BrokenPipeError:  # the reader went away (`ros2 topic list | head -1`)
        sys.stdout = None
        return 0
    except RuntimeError as error:
        if os.environ.get('ROS2CLI_TRACEBACK'):
            raise
        result = str(error)
    except Exception as error:  # the promise: one line, never a traceback
        if type(error).__name__ == 'ExternalShutdownException':
            return signal.SIGTERM
        if os.environ.get('ROS2CLI_TRACEBACK'):
            raise
        result = f'ros2: {type(error).__name__}: {one_line(str(error))}'
    if isinstance(result, str):
        print(result, file=sys.stderr)
        return 1
    return result or 0


def can_end_without_static_cleanup() -> bool:
    """Whether the process can end with os._exit: no ROS participant left, no thread still working.

    A participant is left while rclpy's default context is initialized and not shut down (a
    command that failed before its clean-up); rclpy's shutdown destroys it, so the graph hears it
    leave. A non-daemon thread other than the main one would be waited for by a normal exit.
    """
    rclpy = sys.modules.get('rclpy')
    if rclpy is not None and rclpy.ok():
        return False
    main_thread = threading.main_thread()
    return not any(thread is not main_thread and not thread.daemon and thread.is_alive()
                   for thread in threading.enumerate())


def console_main() -> NoReturn:
    """The `ros2` executable: main(), then end the process without C++'s static clean-up.

    Fast DDS's participant factory, a static object made with the process's first participant,
    sleeps 100 ms in its destructor at exit: a sixth of a cold `ros2 node list`, paid after the
    answer is printed. Once main() is done and can_end_without_static_cleanup() holds, the at-exit
    handlers run (coverage, the venv's rclpy repair), stdout and stderr are flushed and the
    process ends with os._exit and main()'s exit code; otherwise it exits the ordinary way.
    """
    code = main()
    if not can_end_without_static_cleanup():
        sys.exit(code)
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            if stream is not None:
                stream.flush()
        except (OSError, ValueError):  # a reader that went away, a closed stream: nothing to save
            pass
    os._exit(code)


if __name__ == '__main__':
    console_main()
