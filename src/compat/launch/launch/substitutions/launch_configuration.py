"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import LaunchConfiguration

__all__ = ['LaunchConfiguration']
