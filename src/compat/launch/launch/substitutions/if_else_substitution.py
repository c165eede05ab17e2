"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import IfElseSubstitution

__all__ = ['IfElseSubstitution']
