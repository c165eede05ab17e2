"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import NotEqualsSubstitution

__all__ = ['NotEqualsSubstitution']
