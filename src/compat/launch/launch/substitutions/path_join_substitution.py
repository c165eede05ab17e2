"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import PathJoinSubstitution

__all__ = ['PathJoinSubstitution']
