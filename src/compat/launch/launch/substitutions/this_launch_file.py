"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import ThisLaunchFile

__all__ = ['ThisLaunchFile']
