"""Upstream's module path; implemented in launch.launch_description_sources."""

from launch.launch_description_sources import (
    InvalidPythonLaunchFileError,
    get_launch_description_from_python_launch_file,
    load_python_launch_file_as_module,
)

__all__ = [
    'InvalidPythonLaunchFileError',
    'get_launch_description_from_python_launch_file',
    'load_python_launch_file_as_module',
]
