"""LaunchDescriptionSource: where a launch description comes from (a file of some format)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from launch.launch_context import LaunchContext
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import describe_substitutions
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_description import LaunchDescription


class LaunchDescriptionSource:
    """Loads a launch description from a location, once that location is known."""

    def __init__(self, launch_description: LaunchDescription | None = None,
                 location: SomeSubstitutionsType = '<string>', method: str = 'unspecified') -> None:
        self._launch_description = launch_description
        self._location = normalize_to_list_of_substitutions(location)
        self._expanded_location: str | None = None
        self.method = method

    @property
    def location(self) -> str:
        if self._expanded_location is None:
            raise RuntimeError('the location of a launch description source is known only once it '
                               'has been performed')
        return self._expanded_location

    def describe(self) -> str:
        return describe_substitutions(self._location)

    def _load(self, location: str) -> LaunchDescription:
        if self._launch_description is None:
            raise RuntimeError('this launch description source has no description')
        return self._launch_description

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        location = perform_substitutions(context, self._location)
        if self._launch_description is None or location != self._expanded_location:
            self._expanded_location = location
            self._launch_description = self._load(location)
        return self._launch_description

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """The description when the location needs no runtime values; None otherwise."""
        try:
            return self.get_launch_description(LaunchContext())
        except Exception:
            return None


def _check_file(path: str) -> None:
    """A clear error for a launch file path that is missing or not a file."""
    if not os.path.exists(path):
        raise FileNotFoundError(f"launch file '{path}' does not exist")
    if not os.path.isfile(path):
        raise IsADirectoryError(f"launch file '{path}' is not a file")
