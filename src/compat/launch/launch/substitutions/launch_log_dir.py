"""Upstream's module path; implemented in launch.substitutions."""

from launch.substitutions import LaunchLogDir

__all__ = ['LaunchLogDir']
