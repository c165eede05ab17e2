"""What `ros2 launch` does, as plain functions: find the file, parse arguments, show, launch."""

from __future__ import annotations

import os
from collections.abc import Iterable

from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from launch import LaunchDescription, LaunchIntrospector, LaunchService
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import (
    AnyLaunchDescriptionSource,
    get_launch_description_from_any_launch_file,
)
from launch.substitution import describe_substitutions


class MultipleLaunchFilesError(RuntimeError):
    """The launch file's name was found more than once below the package's share directory."""

    pass


def get_share_file_path_from_package(package_name: str, file_name: str) -> str:
    """The one file of that name anywhere below the package's share directory."""
    try:
        share = get_package_share_directory(package_name)
    except PackageNotFoundError as error:
        reason = error.args[0] if error.args else error
        raise RuntimeError(f"Package '{package_name}' not found: {reason}") from None
    except (ValueError, OSError) as error:
        raise RuntimeError(f"Package '{package_name}' not found: {error}") from None
    found = [os.path.join(root, file_name) for root, _dirs, files in os.walk(share, followlinks=True)
             if file_name in files]
    if not found:
        raise RuntimeError(f"file '{file_name}' was not found in the share directory of package "
                           f"'{package_name}' which is at '{share}'")
    if len(found) > 1:
        raise MultipleLaunchFilesError(f"file '{file_name}' was found more than once in the share "
                                       f"directory of package '{package_name}': {sorted(found)}")
    return found[0]


def parse_launch_arguments(arguments: Iterable[str]) -> list[tuple[str, str]]:
    """name:=value pairs (split at the first ':='); a repeated name keeps the last value."""
    parsed: dict[str, str] = {}
    for argument in arguments:
        name, separator, value = argument.partition(':=')
        if not separator or not name or not value:
            raise RuntimeError(f"malformed launch argument '{argument}', expected format '<name>:=<value>'")
        parsed.pop(name, None)
        parsed[name] = value
    return list(parsed.items())


def load_launch_file(path: str) -> LaunchDescription:
    """Load without running; a broken file is a RuntimeError with the loader's message."""
    try:
        return get_launch_description_from_any_launch_file(path)
    except Exception as error:
        raise RuntimeError(str(error)) from None


def format_arguments_of_launch_file(path: str) -> str:
    """The `ros2 launch -s` text: each declared argument with its description and default, as upstream.

    Arguments that are only used under some condition are starred, with a note at the end.
    """
    arguments = load_launch_file(path).get_launch_arguments(conditional_inclusion=True)
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    for argument in arguments:
        lines.append('')
        star = '*' if argument._conditionally_included else ''
        lines.append(f"    '{argument.name}':{star}")
        lines.append(f'        {argument.description}')
        if argument.default_value is not None:
            lines.append(f'        (default: {describe_substitutions(argument.default_value)})')
    if not arguments:
        lines.append('\n  No arguments.')
    elif any(argument._conditionally_included for argument in arguments):
        lines.append('\n* argument(s) which are only used if specific conditions occur')
    return '\n'.join(lines)


def format_launch_description(path: str) -> str:
    """An indented tree of what the file would do (`ros2 launch -p`)."""
    return LaunchIntrospector().format_launch_description(
        load_launch_file(path), title=f'<launch.LaunchDescription from {path}>')


def launch_a_launch_file(path: str, launch_arguments: list[tuple[str, str]], *, noninteractive: bool,
                         debug: bool, argv: list[str] | None = None) -> int:
    """Run the file as launch's one LaunchService does; its return code."""
    service = LaunchService(argv=argv or [], noninteractive=noninteractive, debug=debug)
    service.include_launch_description(LaunchDescription([
        IncludeLaunchDescription(AnyLaunchDescriptionSource(path), launch_arguments=launch_arguments)]))
    return service.run()
