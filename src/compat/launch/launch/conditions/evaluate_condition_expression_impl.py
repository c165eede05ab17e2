"""evaluate_condition_expression: the truth of a condition's text."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.conditions.invalid_condition_expression_error import InvalidConditionExpressionError
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


VALID_TRUE = ('true', '1')
VALID_FALSE = ('false', '0')


def evaluate_condition_expression(context: LaunchContext, expression: SomeSubstitutionsType) -> bool:
    """'true'/'1' or 'false'/'0', any case and surrounding whitespace; anything else is an error."""
    substitutions = normalize_to_list_of_substitutions(expression)
    text = perform_substitutions(context, substitutions).strip().lower()
    if text in VALID_TRUE:
        return True
    if text in VALID_FALSE:
        return False
    raise InvalidConditionExpressionError(text, substitutions)
