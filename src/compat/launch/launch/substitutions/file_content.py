"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import FileContent

__all__ = ['FileContent']
