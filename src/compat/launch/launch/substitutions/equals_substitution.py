"""EqualsSubstitution: whether two values are equal."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions
from launch.utilities.type_utils import is_substitution

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def _comparable(value: object) -> list[Substitution]:
    """An EqualsSubstitution side: None is '', a bool is 'true'/'false', other values their str()."""
    if is_substitution(value):
        return normalize_to_list_of_substitutions(value)  # type: ignore[arg-type]
    if value is None:
        return [TextSubstitution(text='')]
    if isinstance(value, bool):
        return [TextSubstitution(text=str(value).lower())]
    return [TextSubstitution(text=str(value))]


def _is_boolean_text(text: str) -> bool:
    return text.lower() in ('true', 'false', '1', '0')


def _is_number_text(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


class EqualsSubstitution(Substitution):
    """'true' when both sides are equal, else 'false'.

    They are compared as booleans if both are true/false/1/0, as numbers (close enough) if both are
    numbers, else as text.  Sides may be any value: None, bools, numbers.
    """

    def __init__(self, left: object, right: object) -> None:
        self.left = _comparable(left)
        self.right = _comparable(right)

    def perform(self, context: LaunchContext) -> str:
        left = perform_substitutions(context, self.left)
        right = perform_substitutions(context, self.right)
        if _is_boolean_text(left) and _is_boolean_text(right):
            equal = (left.lower() in ('true', '1')) == (right.lower() in ('true', '1'))
        elif _is_number_text(left) and _is_number_text(right):
            equal = math.isclose(float(left), float(right))
        else:
            equal = left == right
        return str(equal).lower()

    def describe(self) -> str:
        left, right = describe_substitutions(self.left), describe_substitutions(self.right)
        return f'EqualsSubstitution({left}, {right})'
