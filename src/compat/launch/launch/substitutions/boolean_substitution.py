"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import (
    AllSubstitution,
    AndSubstitution,
    AnySubstitution,
    NotSubstitution,
    OrSubstitution,
)

__all__ = ['AllSubstitution', 'AndSubstitution', 'AnySubstitution', 'NotSubstitution', 'OrSubstitution']
