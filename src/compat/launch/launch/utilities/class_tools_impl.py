"""Upstream's module path; implemented in launch.utilities."""

from launch.utilities import is_a, is_a_subclass

__all__ = ['is_a', 'is_a_subclass']
