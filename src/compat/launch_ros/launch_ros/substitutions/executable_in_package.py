"""Upstream's module path; implemented in launch_ros.substitutions."""

from launch_ros.substitutions import ExecutableInPackage

__all__ = ['ExecutableInPackage']
