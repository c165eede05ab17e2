"""Upstream's module path; implemented in launch.event_handlers."""

from launch.event_handlers import OnIncludeLaunchDescription

__all__ = ['OnIncludeLaunchDescription']
