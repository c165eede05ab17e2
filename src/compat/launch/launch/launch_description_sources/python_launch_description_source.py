"""PythonLaunchDescriptionSource: a Python launch file."""

from __future__ import annotations

from launch.invalid_launch_file_error import InvalidLaunchFileError
from launch.launch_description import LaunchDescription
from launch.launch_description_source import LaunchDescriptionSource, _check_file
from launch.launch_description_sources.python_launch_file_utilities import (
    InvalidPythonLaunchFileError,
    get_launch_description_from_python_launch_file,
)
from launch.some_substitutions_type import SomeSubstitutionsType


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
