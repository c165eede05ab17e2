"""Launch description sources for Python, XML and YAML files, and one that picks by extension."""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
from collections.abc import Callable
from typing import TYPE_CHECKING

from launch.frontend.parser import InvalidFrontendLaunchFileError
from launch.launch_description_source import LaunchDescriptionSource
from launch.some_substitutions_type import SomeSubstitutionsType

if TYPE_CHECKING:
    from launch.launch_description import LaunchDescription

__all__ = [
    'AnyLaunchDescriptionSource', 'FrontendLaunchDescriptionSource', 'InvalidFrontendLaunchFileError',
    'InvalidLaunchFileError',
    'InvalidPythonLaunchFileError', 'LaunchDescriptionSource', 'PythonLaunchDescriptionSource',
    'get_launch_description_from_any_launch_file', 'get_launch_description_from_frontend_launch_file',
    'get_launch_description_from_python_launch_file',
    'load_python_launch_file_as_module',
]


class InvalidPythonLaunchFileError(Exception):
    pass


class InvalidLaunchFileError(Exception):
    """No loader could read the file; the message lists what each loader said."""

    def __init__(self, extension: str = '', *, likely_errors: list[Exception] | None = None) -> None:
        errors = likely_errors or []
        if not errors:
            message = 'The launch file may have a syntax error, or its format is unknown'
        else:
            several = 'multiple exceptions' if len(errors) > 1 else 'exception'
            lines = [f'Caught {several} when trying to load file of format [{extension}]:']
            lines += [f' - {type(error).__name__}: {error}' for error in errors]
            message = '\n'.join(lines)
        super().__init__(message)


def load_python_launch_file_as_module(python_launch_file_path: str) -> object:
    """Execute the file as a fresh module named python_launch_file, with __file__ set."""
    loader = importlib.machinery.SourceFileLoader('python_launch_file', python_launch_file_path)
    spec = importlib.util.spec_from_loader('python_launch_file', loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def get_launch_description_from_python_launch_file(python_launch_file_path: str) -> LaunchDescription:
    from launch.launch_description import LaunchDescription

    module = load_python_launch_file_as_module(python_launch_file_path)
    generate = getattr(module, 'generate_launch_description', None)
    if not callable(generate):
        raise InvalidPythonLaunchFileError(
            f"launch file at '{python_launch_file_path}' does not contain the required function "
            "'generate_launch_description()'")
    description = generate()
    if not isinstance(description, LaunchDescription):
        raise InvalidPythonLaunchFileError(
            f"generate_launch_description() of launch file at '{python_launch_file_path}' returned "
            f"'{type(description).__name__}' instead of a launch.LaunchDescription")
    return description


def _frontend_loader(format_name: str) -> Callable[[str], LaunchDescription]:
    def load(path: str) -> LaunchDescription:
        from launch.frontend import load_launch_file

        return load_launch_file(path, format_name)
    return load


# Extension -> (format name shown in errors, loader).  A file whose extension is none of
# these is tried with every loader.
_LOADERS: dict[str, Callable[[str], LaunchDescription]] = {
    'py': get_launch_description_from_python_launch_file,
    'xml': _frontend_loader('xml'),
    'yaml': _frontend_loader('yaml'),
    'yml': _frontend_loader('yaml'),
}


def _check_file(path: str) -> None:
    if not os.path.exists(path):
        raise FileNotFoundError(f"launch file '{path}' does not exist")
    if not os.path.isfile(path):
        raise IsADirectoryError(f"launch file '{path}' is not a file")


def get_launch_description_from_any_launch_file(launch_file_path: str) -> LaunchDescription:
    """Load by extension; other extensions try every format.

    Unlike upstream, a known extension is read only with its own loader, so that a syntax error
    in a .py file is reported once instead of next to what the XML parser made of it.
    """
    _check_file(launch_file_path)
    extension = os.path.splitext(launch_file_path)[1].lstrip('.')
    loaders = [_LOADERS[extension]] if extension in _LOADERS else list(_LOADERS.values())[:3]
    errors: list[Exception] = []
    for load in loaders:
        try:
            return load(launch_file_path)
        except Exception as error:
            errors.append(error)
    raise InvalidLaunchFileError(extension, likely_errors=errors)


def get_launch_description_from_frontend_launch_file(frontend_launch_file_path: str) -> LaunchDescription:
    """Read an XML or YAML launch file (format by extension, else tried as both)."""
    from launch.frontend import Parser

    try:
        root, parser = Parser.load(frontend_launch_file_path)
    except Exception as error:
        raise InvalidFrontendLaunchFileError(str(error)) from error
    return parser.parse_description(root)


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, 'interpreted python launch file')

    def _load(self, location: str) -> LaunchDescription:
        _check_file(location)
        try:
            return get_launch_description_from_python_launch_file(location)
        except InvalidPythonLaunchFileError:
            raise
        except Exception as error:
            raise InvalidLaunchFileError('py', likely_errors=[error]) from error


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """An XML or YAML file: the format is the subclass's, else chosen by the extension."""

    format_name = ''

    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, f'interpreted {self.format_name} launch file')

    def _load(self, location: str) -> LaunchDescription:
        _check_file(location)
        format_name = self.format_name or (
            'yaml' if location.endswith(('.yaml', '.yml')) else 'xml')
        try:
            return _frontend_loader(format_name)(location)
        except Exception as error:
            raise InvalidLaunchFileError(format_name, likely_errors=[error]) from error


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, 'interpreted launch file')

    def _load(self, location: str) -> LaunchDescription:
        return get_launch_description_from_any_launch_file(location)
