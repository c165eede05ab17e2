"""AnyLaunchDescriptionSource: a launch file of any format, chosen by its extension."""

from __future__ import annotations

from launch.launch_description import LaunchDescription
from launch.launch_description_source import LaunchDescriptionSource
from launch.launch_description_sources.any_launch_file_utilities import (
    get_launch_description_from_any_launch_file,
)
from launch.some_substitutions_type import SomeSubstitutionsType


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, 'interpreted launch file')

    def _load(self, location: str) -> LaunchDescription:
        return get_launch_description_from_any_launch_file(location)
