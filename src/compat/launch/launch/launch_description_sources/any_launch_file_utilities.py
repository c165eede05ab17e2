"""Loading a launch file of any format: Python, or one of the frontend's (XML, YAML)."""

from __future__ import annotations

import os
from collections.abc import Callable

from launch.frontend.parser import Parser, load_launch_file
from launch.invalid_launch_file_error import InvalidLaunchFileError
from launch.launch_description import LaunchDescription
from launch.launch_description_source import _check_file
from launch.launch_description_sources.python_launch_file_utilities import (
    get_launch_description_from_python_launch_file,
)


def _frontend_loader(format_name: str) -> Callable[[str], LaunchDescription]:
    def load(path: str) -> LaunchDescription:
        return load_launch_file(path, format_name)
    return load


def _loaders(extension: str) -> list[Callable[[str], LaunchDescription]]:
    """The loader of the extension's format; every loader (Python first) for another extension."""
    if extension == 'py':
        return [get_launch_description_from_python_launch_file]
    formats = Parser.load_parser_implementations()
    for format_name, implementation in formats.items():
        if extension in implementation.get_file_extensions():
            return [_frontend_loader(format_name)]
    return [get_launch_description_from_python_launch_file, *map(_frontend_loader, formats)]


def get_launch_description_from_any_launch_file(launch_file_path: str) -> LaunchDescription:
    """Load by extension; other extensions try every format.

    Unlike upstream, a known extension is read only with its own loader, so that a syntax error
    in a .py file is reported once instead of next to what the XML parser made of it.
    """
    _check_file(launch_file_path)
    extension = os.path.splitext(launch_file_path)[1].lstrip('.')
    errors: list[Exception] = []
    for load in _loaders(extension):
        try:
            return load(launch_file_path)
        except Exception as error:
            errors.append(error)
    raise InvalidLaunchFileError(extension, likely_errors=errors)
