"""Upstream's module path; implemented in launch.launch_description_sources."""

from launch.launch_description_sources import (
    InvalidFrontendLaunchFileError,
    get_launch_description_from_frontend_launch_file,
)

__all__ = ['InvalidFrontendLaunchFileError', 'get_launch_description_from_frontend_launch_file']
