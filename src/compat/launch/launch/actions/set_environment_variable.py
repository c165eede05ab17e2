"""Upstream's module path; implemented in launch.actions.environment_actions."""

from launch.actions.environment_actions import SetEnvironmentVariable

__all__ = ['SetEnvironmentVariable']
