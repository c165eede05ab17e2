"""Upstream's module path; implemented in launch.actions.environment_actions."""

from launch.actions.environment_actions import ResetEnvironment

__all__ = ['ResetEnvironment']
