"""Upstream's module path; implemented in launch.conditions."""

from launch.conditions import LaunchConfigurationEquals

__all__ = ['LaunchConfigurationEquals']
