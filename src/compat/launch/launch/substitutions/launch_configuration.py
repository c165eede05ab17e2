"""LaunchConfiguration: the value of a launch configuration."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def _normalize_default(default: object) -> list[Substitution]:
    """Defaults may be plain values (sigterm_timeout defaults to 5): those become their str()."""
    if isinstance(default, (str, Substitution)):
        return normalize_to_list_of_substitutions(default)
    if isinstance(default, Iterable):
        return [item if isinstance(item, Substitution) else TextSubstitution(text=str(item))
                for item in default]
    return [TextSubstitution(text=str(default))]


class LaunchConfiguration(Substitution):
    """The value of a launch configuration (a declared argument, a `let`...)."""

    def __init__(self, variable_name: SomeSubstitutionsType, *, default: object = None) -> None:
        self.variable_name = normalize_to_list_of_substitutions(variable_name)
        self.default = None if default is None else _normalize_default(default)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.variable_name)
        if name in context.launch_configurations:
            return context.launch_configurations[name]
        if self.default is None:
            raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
        return perform_substitutions(context, self.default)

    def describe(self) -> str:
        return f'LaunchConfig({describe_substitutions(self.variable_name)})'
