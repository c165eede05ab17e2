"""Upstream's module path; implemented in launch.launch_description_sources."""

from launch.launch_description_sources import InvalidLaunchFileError

__all__ = ['InvalidLaunchFileError']
