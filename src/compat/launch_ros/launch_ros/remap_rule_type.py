"""Upstream's type names for Node(remappings=...)."""

from __future__ import annotations

from collections.abc import Iterable

from launch.substitution import SomeSubstitutionsType, Substitution

__all__ = ['RemapRules', 'SomeRemapRules']

SomeRemapRules = Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]
RemapRules = Iterable[tuple[list[Substitution], list[Substitution]]]
