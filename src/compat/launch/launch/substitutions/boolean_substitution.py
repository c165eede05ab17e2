"""The boolean substitutions: not, and, or, any, all."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.conditions.evaluate_condition_expression_impl import evaluate_condition_expression
from launch.conditions.invalid_condition_expression_error import InvalidConditionExpressionError
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def _truth(context: LaunchContext, value: list[Substitution]) -> bool:
    """A boolean operand; one that is not true/false/1/0 is a SubstitutionFailure, as upstream."""
    try:
        return evaluate_condition_expression(context, value)
    except InvalidConditionExpressionError:
        text = perform_substitutions(context, value)
        raise SubstitutionFailure(f"'{text}' is not a valid boolean value, expected true, false, 1 or 0 "
                                  f"(expanded from {describe_substitutions(value)})") from None


class NotSubstitution(Substitution):
    def __init__(self, value: SomeSubstitutionsType) -> None:
        self.value = normalize_to_list_of_substitutions(value)

    def perform(self, context: LaunchContext) -> str:
        return str(not _truth(context, self.value)).lower()


class AndSubstitution(Substitution):
    def __init__(self, left: SomeSubstitutionsType, right: SomeSubstitutionsType) -> None:
        self.left = normalize_to_list_of_substitutions(left)
        self.right = normalize_to_list_of_substitutions(right)

    def perform(self, context: LaunchContext) -> str:
        return str(_truth(context, self.left) and _truth(context, self.right)).lower()


class OrSubstitution(AndSubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(_truth(context, self.left) or _truth(context, self.right)).lower()


class AnySubstitution(Substitution):
    def __init__(self, *args: SomeSubstitutionsType) -> None:
        self.args = [normalize_to_list_of_substitutions(arg) for arg in args]

    def perform(self, context: LaunchContext) -> str:
        return str(any(_truth(context, arg) for arg in self.args)).lower()


class AllSubstitution(AnySubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(all(_truth(context, arg) for arg in self.args)).lower()
