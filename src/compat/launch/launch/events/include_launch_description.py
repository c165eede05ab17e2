"""Upstream's module path; implemented in launch.events."""

from launch.events import IncludeLaunchDescription

__all__ = ['IncludeLaunchDescription']
