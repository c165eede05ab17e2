"""FrontendLaunchDescriptionSource: an XML or YAML launch file."""

from __future__ import annotations

from launch.frontend.parser import InvalidFrontendLaunchFileError, load_launch_file
from launch.launch_description import LaunchDescription
from launch.launch_description_source import LaunchDescriptionSource, _check_file
from launch.some_substitutions_type import SomeSubstitutionsType


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
            return load_launch_file(location, format_name)
        except Exception as error:
            raise InvalidFrontendLaunchFileError(format_name, likely_errors=[error]) from error
