"""Upstream's module path of SomeSubstitutionsType."""

from launch.substitution import SomeSubstitutionsType

__all__ = ['SomeSubstitutionsType']
