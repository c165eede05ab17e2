"""Upstream's type names for Node(remappings=...): as given, and once normalised."""

from __future__ import annotations

from collections.abc import Iterable

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution

__all__ = ['RemapRule', 'RemapRules', 'SomeRemapRule', 'SomeRemapRules']

SomeRemapRule = tuple[SomeSubstitutionsType, SomeSubstitutionsType]
SomeRemapRules = Iterable[SomeRemapRule]
RemapRule = tuple[tuple[Substitution, ...], tuple[Substitution, ...]]
RemapRules = Iterable[RemapRule]
