"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import LaunchConfigurationNotEquals

__all__ = ['LaunchConfigurationNotEquals']
