"""Upstream's module path; implemented in launch.substitution."""

from launch.substitution import TextSubstitution

__all__ = ['TextSubstitution']
