"""Upstream's module path; implemented in launch.launch_description_sources."""

from launch.launch_description_sources import (
    InvalidLaunchFileError,
    get_launch_description_from_any_launch_file,
)

__all__ = ['InvalidLaunchFileError', 'get_launch_description_from_any_launch_file']
