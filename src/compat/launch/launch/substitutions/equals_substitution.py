"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import EqualsSubstitution

__all__ = ['EqualsSubstitution']
