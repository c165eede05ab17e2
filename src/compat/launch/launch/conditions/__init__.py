"""Conditions on actions: IfCondition, UnlessCondition and the launch-configuration comparisons."""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

from launch.condition import Condition
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import describe_substitutions
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = [
    'IfCondition', 'InvalidConditionExpressionError', 'LaunchConfigurationEquals',
    'LaunchConfigurationNotEquals', 'UnlessCondition', 'evaluate_condition_expression',
]

VALID_TRUE = ('true', '1')
VALID_FALSE = ('false', '0')


class InvalidConditionExpressionError(ValueError):
    def __init__(self, expression: str, substitutions: list) -> None:
        super().__init__(
            f'invalid condition expression, expected one of [true, 1, false, 0] but got '
            f"'{expression}', expanded from '{describe_substitutions(substitutions)}'")


def evaluate_condition_expression(context: LaunchContext, expression: SomeSubstitutionsType) -> bool:
    """'true'/'1' or 'false'/'0', any case and surrounding whitespace; anything else is an error."""
    substitutions = normalize_to_list_of_substitutions(expression)
    text = perform_substitutions(context, substitutions).strip().lower()
    if text in VALID_TRUE:
        return True
    if text in VALID_FALSE:
        return False
    raise InvalidConditionExpressionError(text, substitutions)


class IfCondition(Condition):
    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        self._expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=lambda ctx: evaluate_condition_expression(ctx, self._expression))

    def describe(self) -> str:
        return f'IfCondition({describe_substitutions(self._expression)})'


class UnlessCondition(Condition):
    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        self._expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=lambda ctx: not evaluate_condition_expression(ctx, self._expression))

    def describe(self) -> str:
        return f'UnlessCondition({describe_substitutions(self._expression)})'


class LaunchConfigurationEquals(Condition):
    """Deprecated upstream in favour of EqualsSubstitution; kept for old launch files."""

    def __init__(self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None) -> None:
        warnings.warn('The LaunchConfigurationEquals and LaunchConfigurationNotEquals Conditions are '
                      'deprecated. Use the EqualsSubstitution and NotEqualsSubstitution substitutions '
                      'instead.', DeprecationWarning, stacklevel=2)
        self._name = launch_configuration_name
        self._expected = (None if expected_value is None
                          else normalize_to_list_of_substitutions(expected_value))
        super().__init__(predicate=self._equals)

    def _equals(self, context: LaunchContext) -> bool:
        expected = None if self._expected is None else perform_substitutions(context, self._expected)
        return context.launch_configurations.get(self._name) == expected


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    def _equals(self, context: LaunchContext) -> bool:
        return not super()._equals(context)
