"""`ros2`: parse `ros2 <command> ...` with argparse and hand over to the command's module."""

import argparse
import importlib
import signal
import sys
from types import ModuleType

from ros2cli.command_table import COMMANDS


class CommandUnavailable(Exception):
    """A command whose package is not installed."""


def load_command(name: str) -> ModuleType:
    module_name, package = COMMANDS[name]
    try:
        return importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        if error.name and module_name.startswith(error.name):
            raise CommandUnavailable(
                f"ros2: the '{name}' command needs the package '{package}', which is not "
                'installed in this environment') from None
        raise


def build_parser(argv: list[str]) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog='ros2', description='ros2 is an extensible command-line tool for ROS 2.',
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument(
        '--use-python-default-buffering', action='store_true',
        help='Do not force line buffering of stdout; use Python\'s default buffering')
    subparsers = parser.add_subparsers(
        title='Commands', metavar='Call `ros2 <command> -h` for more detailed usage.')
    # Only the chosen command is imported; `ros2 -h` lists the rest by name.
    chosen = next((arg for arg in argv if not arg.startswith('-')), None)
    for name in sorted(COMMANDS):
        if name == chosen:
            module = load_command(name)
            command_parser = subparsers.add_parser(name, help=module.DESCRIPTION,
                                                   description=module.DESCRIPTION)
            module.add_arguments(command_parser, f'ros2 {name}')
            command_parser.set_defaults(_main=module.main, _parser=command_parser)
        else:
            subparsers.add_parser(name, help=f'`ros2 {name} -h` for its verbs and options')
    return parser


def main(argv: list[str] | None = None) -> int | str:
    argv = sys.argv[1:] if argv is None else argv
    try:
        parser = build_parser(argv)
    except CommandUnavailable as error:
        print(error, file=sys.stderr)
        return 1
    args = parser.parse_args(argv)
    if not args.use_python_default_buffering:
        sys.stdout.reconfigure(line_buffering=True)
    command_main = getattr(args, '_main', None)
    if command_main is None:
        parser.print_help()
        return 0
    try:
        result = command_main(args)
    except KeyboardInterrupt:
        return signal.SIGINT
    except RuntimeError as error:
        return str(error)
    if isinstance(result, str):
        print(result, file=sys.stderr)
        return 1
    return result or 0


if __name__ == '__main__':
    sys.exit(main())
