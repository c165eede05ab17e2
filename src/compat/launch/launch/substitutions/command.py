"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import Command

__all__ = ['Command']
