"""Substitutions: pieces of text computed lazily, when the action that owns them executes."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed (missing configuration, package, executable...)."""


class Substitution:
    """Base class: perform(context) gives the text, describe() a readable form without a context."""

    def perform(self, context: LaunchContext) -> str:
        raise NotImplementedError(type(self).__name__)

    def describe(self) -> str:
        return type(self).__name__ + '(...)'


class TextSubstitution(Substitution):
    """Literal text."""

    def __init__(self, *, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected 'str' got '{type(text)}'")
        self.text = text

    def perform(self, context: LaunchContext) -> str:
        return self.text

    def describe(self) -> str:
        return repr(self.text)


SomeSubstitutionsType = str | Substitution | Iterable[str | Substitution]
SomeSubstitutionsType_types_tuple = (str, Substitution, Iterable)


def _normalize_item(item: object) -> Substitution:
    if isinstance(item, str):
        return TextSubstitution(text=item)
    if isinstance(item, Substitution):
        return item
    raise TypeError(f"Failed to normalize given item of type '{type(item)}', when only 'str' or "
                    "'launch.Substitution' were expected.")


def normalize_to_list_of_substitutions(subs: SomeSubstitutionsType) -> list[Substitution]:
    """A str, a Substitution or an iterable of both, as a list of Substitutions."""
    if isinstance(subs, (str, Substitution)):
        return [_normalize_item(subs)]
    return [_normalize_item(item) for item in subs]


def perform_substitutions(context: LaunchContext, subs: Iterable[Substitution]) -> str:
    """The concatenated text of the substitutions."""
    return ''.join(sub.perform(context) for sub in subs)


def describe_substitutions(subs: Iterable[Substitution]) -> str:
    return ' + '.join(sub.describe() for sub in subs)

