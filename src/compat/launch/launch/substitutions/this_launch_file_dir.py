"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import ThisLaunchFileDir

__all__ = ['ThisLaunchFileDir']
