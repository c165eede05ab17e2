"""Upstream's type names for Node(remappings=...)."""

from __future__ import annotations

from collections.abc import Iterable

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution

__all__ = ['RemapRules', 'SomeRemapRules']

SomeRemapRules = Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]
RemapRules = Iterable[tuple[list[Substitution], list[Substitution]]]
