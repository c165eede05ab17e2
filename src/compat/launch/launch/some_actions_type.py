"""Upstream's module path; implemented in launch.action."""

from launch.action import SomeActionsType, SomeActionsType_types_tuple

__all__ = ['SomeActionsType', 'SomeActionsType_types_tuple']
