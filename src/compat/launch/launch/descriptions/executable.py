"""Upstream's module path; implemented in launch.descriptions."""

from launch.descriptions import Executable

__all__ = ['Executable']
