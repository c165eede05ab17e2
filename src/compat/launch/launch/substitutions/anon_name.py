"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import AnonName

__all__ = ['AnonName']
