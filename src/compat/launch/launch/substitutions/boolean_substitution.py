"""The boolean substitutions: not, and, or, any, all."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.substitution_failure import SubstitutionFailure
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions
from launch.utilities.type_utils import coerce_to_type

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def _truth(context: LaunchContext, value: list[Substitution]) -> bool:
    """A boolean operand, read as Jazzy reads a bool's text: true/false, 1/0, yes/no, on/off.

    Anything else is a SubstitutionFailure, as upstream.
    """
    text = perform_substitutions(context, value)
    try:
        return coerce_to_type(text, bool)
    except ValueError:
        origin = describe_substitutions(value)
        raise SubstitutionFailure(f"'{text}' is not a valid boolean value, expected true/false, 1/0, "
                                  f'yes/no or on/off (expanded from {origin})') from None


def _truths(context: LaunchContext, values: list[list[Substitution]]) -> list[bool]:
    """Every operand's truth: each is performed and checked, even once the result is decided."""
    return [_truth(context, value) for value in values]


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
        return str(all(_truths(context, [self.left, self.right]))).lower()


class OrSubstitution(AndSubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(any(_truths(context, [self.left, self.right]))).lower()


class AnySubstitution(Substitution):
    def __init__(self, *args: SomeSubstitutionsType) -> None:
        self.args = [normalize_to_list_of_substitutions(arg) for arg in args]

    def perform(self, context: LaunchContext) -> str:
        return str(any(_truths(context, self.args))).lower()


class AllSubstitution(AnySubstitution):
    def perform(self, context: LaunchContext) -> str:
        return str(all(_truths(context, self.args))).lower()
