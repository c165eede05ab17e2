"""Upstream's module path; implemented in launch.utilities."""

from launch.utilities import ensure_argument_type

__all__ = ['ensure_argument_type']
