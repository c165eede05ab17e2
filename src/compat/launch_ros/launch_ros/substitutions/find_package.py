"""Upstream's module path; implemented in launch_ros.substitutions."""

from launch_ros.substitutions import FindPackage, FindPackagePrefix, FindPackageShare

__all__ = ['FindPackage', 'FindPackagePrefix', 'FindPackageShare']
