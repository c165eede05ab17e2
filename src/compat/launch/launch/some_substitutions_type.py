"""Upstream's module path of SomeSubstitutionsType."""

from launch.substitution import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple

__all__ = ['SomeSubstitutionsType', 'SomeSubstitutionsType_types_tuple']
