"""InvalidConditionExpressionError: a condition whose text is not true, false, 1 or 0."""

from launch.substitution import describe_substitutions


class InvalidConditionExpressionError(ValueError):
    def __init__(self, expression: str, substitutions: list) -> None:
        super().__init__(
            f'invalid condition expression, expected one of [true, 1, false, 0] but got '
            f"'{expression}', expanded from '{describe_substitutions(substitutions)}'")
