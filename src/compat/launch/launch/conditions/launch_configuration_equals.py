"""LaunchConfigurationEquals: an action executes when a launch configuration has a given value."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

from launch.condition import Condition
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class LaunchConfigurationEquals(Condition):
    """Deprecated upstream in favour of EqualsSubstitution; kept for old launch files."""

    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None) -> None:
        warnings.warn('The LaunchConfigurationEquals and LaunchConfigurationNotEquals Conditions are '
                      'deprecated. Use the EqualsSubstitution and NotEqualsSubstitution substitutions '
                      'instead.', UserWarning, stacklevel=2)  # UserWarning, so launch files show it
        self._name = launch_configuration_name
        self._expected = (None if expected_value is None
                          else normalize_to_list_of_substitutions(expected_value))
        super().__init__(predicate=self._equals)

    def _equals(self, context: LaunchContext) -> bool:
        expected = None if self._expected is None else perform_substitutions(context, self._expected)
        return context.launch_configurations.get(self._name) == expected
