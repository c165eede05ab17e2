"""UnlessCondition: an action executes when an expression is false."""

from __future__ import annotations

from launch.condition import Condition
from launch.conditions.evaluate_condition_expression_impl import evaluate_condition_expression
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import describe_substitutions
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions


class UnlessCondition(Condition):
    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        self._expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=lambda ctx: not evaluate_condition_expression(ctx, self._expression))

    def describe(self) -> str:
        return f'UnlessCondition({describe_substitutions(self._expression)})'
