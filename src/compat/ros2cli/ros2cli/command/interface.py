"""`ros2 interface show | list | package | packages | proto`, from the installed interface files."""

import argparse
import os
import sys
from typing import Any

from ros2cli.command import VerbCommand
from ros2cli.verb import VerbExtension

PRIMITIVES = {'bool', 'byte', 'char', 'float32', 'float64', 'int8', 'uint8', 'int16', 'uint16', 'int32',
              'uint32', 'int64', 'uint64', 'string', 'wstring'}
SECTION_TITLES = (('msg', 'Messages:'), ('srv', 'Services:'), ('action', 'Actions:'))


def _add_kind_filters(parser: argparse.ArgumentParser) -> None:
    group = parser.add_mutually_exclusive_group()
    group.add_argument('-m', '--only-msgs', action='store_true', help='Print out only the messages')
    group.add_argument('-s', '--only-srvs', action='store_true', help='Print out only the services')
    group.add_argument('-a', '--only-actions', action='store_true', help='Print out only the actions')


def _wanted_kinds(args: argparse.Namespace) -> list[str]:
    chosen = [kind for kind, flag in (('msg', args.only_msgs), ('srv', args.only_srvs),
                                      ('action', args.only_actions)) if flag]
    return chosen or ['msg', 'srv', 'action']


def _unknown_package(package: str) -> str:
    from owl_common.hints import did_you_mean
    from rosidl_runtime_py.get_interfaces import interface_index
    return f"Unknown package '{package}'{did_you_mean(package, interface_index())}"


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
    from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
    try:
        share = get_package_share_directory(package)
    except (PackageNotFoundError, ValueError):
        raise RuntimeError(_unknown_package(package)) from None
    path = os.path.join(share, kind, f'{name}.{kind}')
    try:
        with open(path, encoding='utf-8') as definition:
            return definition.read().splitlines()
    except OSError:
        from owl_common.hints import did_you_mean
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
        from ros2cli.completion import any_type_completer, with_completer
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


class ListVerb(VerbExtension):
    """List all interface types available."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the -m/-s/-a filters (only messages, services or actions)."""
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print every installed interface's full name, in a section per kind the filters allow."""
        from rosidl_runtime_py.get_interfaces import interface_index
        index = interface_index()
        wanted = _wanted_kinds(args)
        for kind, title in SECTION_TITLES:
            if kind in wanted:
                print(title)
                for package in sorted(index):
                    for name in index[package][kind]:
                        print(f'    {package}/{kind}/{name}')
        return 0


class PackageVerb(VerbExtension):
    """Output a list of available interface types within one package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and the -m/-s/-a filters."""
        from ros2cli.completion import package_completer, with_completer
        with_completer(parser.add_argument('package_name', help='Name of the ROS package'), package_completer)
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the package's interfaces as full names; the error message for an unknown package."""
        from rosidl_runtime_py.get_interfaces import interface_index
        index = interface_index()
        if args.package_name not in index:
            return _unknown_package(args.package_name)
        for kind in _wanted_kinds(args):
            for name in index[args.package_name][kind]:
                print(f'{args.package_name}/{kind}/{name}')
        return 0


class PackagesVerb(VerbExtension):
    """Output a list of packages that provide interfaces."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the -m/-s/-a filters: only packages with interfaces of that kind."""
        _add_kind_filters(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the packages that provide interfaces of the kinds the filters allow."""
        from rosidl_runtime_py.get_interfaces import interface_index
        wanted = _wanted_kinds(args)
        for package, kinds in sorted(interface_index().items()):
            if any(kinds[kind] for kind in wanted):
                print(package)
        return 0


def default_instance(type_name: str) -> Any:
    """A default message, service request or action goal for an interface name."""
    from rosidl_runtime_py.utilities import InvalidType, import_type
    parts = type_name.split('/')
    kind = parts[1] if len(parts) == 3 else 'msg'
    if kind not in ('msg', 'srv', 'action'):
        raise RuntimeError(f"Invalid name '{type_name}': the middle part must be 'msg', 'srv' or 'action'")
    try:
        type_class = import_type(type_name, kind)
    except InvalidType as error:
        raise RuntimeError(f"The passed interface type '{type_name}' is invalid: {error}") from None
    return {'msg': type_class, 'srv': getattr(type_class, 'Request', None),
            'action': getattr(type_class, 'Goal', None)}[kind]()


class ProtoVerb(VerbExtension):
    """Output an interface prototype."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the type and --no-quotes."""
        from ros2cli.completion import any_type_completer, with_completer
        with_completer(parser.add_argument(
            'type', help="Show an interface definition (e.g. 'std_msgs/msg/String')"
        ), any_type_completer)
        parser.add_argument('--no-quotes', action='store_true', help='if true output has no outer quotes.')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print a default instance as YAML, in double quotes unless --no-quotes.

        For a service it is the request, for an action the goal; an invalid name raises RuntimeError.
        """
        from rosidl_runtime_py.convert import message_to_yaml
        text = message_to_yaml(default_instance(args.type))
        print(text if args.no_quotes else f'"{text}"')
        return 0


class InterfaceCommand(VerbCommand):
    """Show information about ROS interfaces."""

    VERB_GROUP = 'ros2interface.verb'
