"""Upstream's module path; implemented in launch.actions.launch_configuration_actions."""

from launch.actions.launch_configuration_actions import UnsetLaunchConfiguration

__all__ = ['UnsetLaunchConfiguration']
