"""normalize_to_list_of_substitutions: text, a substitution or a list of both, as substitutions."""

from __future__ import annotations

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution


def _normalize_item(item: object) -> Substitution:
    # Lazy: launch.substitutions' modules import this module, so a top-level import would be a cycle.
    from launch.substitutions.text_substitution import TextSubstitution

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
