"""Upstream's module path; implemented in launch.utilities."""

from launch.utilities import create_future

__all__ = ['create_future']
