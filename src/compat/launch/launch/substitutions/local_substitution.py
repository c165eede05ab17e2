"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import LocalSubstitution

__all__ = ['LocalSubstitution']
