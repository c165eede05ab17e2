"""`ros2 interface show`: an interface's definition, nested message types expanded."""

import argparse
import os
import sys

from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from owl_common.hints import did_you_mean

from ros2cli.api.interface import _unknown_package
from ros2cli.completion import any_type_completer, with_completer
from ros2cli.verb import VerbExtension

PRIMITIVES = {'bool', 'byte', 'char', 'float32', 'float64', 'int8', 'uint8', 'int16', 'uint16', 'int32',
              'uint32', 'int64', 'uint64', 'string', 'wstring'}


def split_comment(line: str) -> tuple[str, str]:
    """(code, comment) of a definition line; a '#' inside quotes does not start a comment."""
    quote = None
    for index, char in enumerate(line):
        if char in '\'"':
            quote = None if quote == char else (quote or char)
        elif char == '#' and quote is None:
            return line[:index].rstrip(), line[index:]
    return line.rstrip(), ''


def nested_type(code: str, package: str) -> tuple[str, str] | None:
    """(package, Name) of the message a field line refers to, or None (primitive, constant, ---)."""
    parts = code.split()
    if len(parts) < 2 or '=' in parts[1]:
        return None
    base = parts[0].split('[', 1)[0].split('<=', 1)[0]
    if base in PRIMITIVES:
        return None
    if '/' in base:
        pieces = base.split('/')
        return pieces[0], pieces[-1]
    return package, base


def definition_lines(package: str, kind: str, name: str) -> list[str]:
    """The lines of <share>/<package>/<kind>/<name>.<kind>; RuntimeError when it is not there."""
    try:
        share = get_package_share_directory(package)
    except (PackageNotFoundError, ValueError):
        raise RuntimeError(_unknown_package(package)) from None
    path = os.path.join(share, kind, f'{name}.{kind}')
    try:
        with open(path, encoding='utf-8') as definition:
            return definition.read().splitlines()
    except OSError:
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
        from rosidl_runtime_py.get_interfaces import interface_index
        known = interface_index().get(package, {}).get(kind, [])
        idl = os.path.join(share, kind, f'{name}.idl')
        raise RuntimeError(f"Could not find the interface '{idl}'{did_you_mean(name, known)}") from None


def render_definition(lines: list[str], package: str, comments: str, level: int = 0) -> list[str]:
    """Definition lines with nested message types expanded beneath their fields, tab-indented.

    comments: 'default' (top level as written, nested without comments), 'all' or 'none'.
    """
    output: list[str] = []
    indent = '\t' * level
    for raw in lines:
        line = raw.rstrip()
        code, _comment = split_comment(line)
        keep_comments = comments == 'all' or (comments == 'default' and level == 0)
        if keep_comments:
            output.append(f'{indent}{line}' if line else '')
        elif code:
            output.append(f'{indent}{code}')
        nested = nested_type(code, package) if code else None
        if nested is not None:
            output += render_definition(definition_lines(nested[0], 'msg', nested[1]), nested[0], comments,
                                        level + 1)
    return output


class ShowVerb(VerbExtension):
    """Output the interface definition."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the type (or '-' to read it from stdin) and --all-comments or --no-comments."""
        with_completer(parser.add_argument(
            'type', help="Show an interface definition (e.g. 'example_interfaces/msg/String'). Passing '-' "
            "reads the argument from stdin (e.g. 'ros2 topic type /chatter | ros2 interface show -')."
        ), any_type_completer)
        group = parser.add_mutually_exclusive_group()
        group.add_argument('--all-comments', action='store_true',
                           help='Show all comments, including for nested interface definitions')
        group.add_argument('--no-comments', action='store_true', help='Show no comments or whitespace')
        self._parser = parser

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the interface's definition, nested message types expanded beneath their fields.

        A malformed name is returned as the error message; an unknown package or interface raises
        RuntimeError (with a 'did you mean' hint).
        """
        type_name = args.type
        if type_name == '-':
            if sys.stdin.isatty():
                self._parser.error('expected stdin pipe')
            type_name = sys.stdin.read().strip()
            if not type_name:
                self._parser.error('the passed value is empty')
        parts = type_name.split('/')
        if len(parts) != 3 or not all(parts):
            return f"Invalid name '{type_name}'. Expected three parts separated by '/'"
        package, kind, name = parts
        if kind not in ('msg', 'srv', 'action'):
            return f"Invalid name '{type_name}': the middle part must be 'msg', 'srv' or 'action'"
        comments = 'all' if args.all_comments else 'none' if args.no_comments else 'default'
        for line in render_definition(definition_lines(package, kind, name), package, comments):
            print(line)
        return 0
