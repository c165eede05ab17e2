"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import EnvironmentVariable

__all__ = ['EnvironmentVariable']
