"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import FindExecutable

__all__ = ['FindExecutable']
