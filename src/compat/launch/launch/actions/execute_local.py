"""Upstream's module path; implemented in launch.actions."""

from launch.actions import ExecuteLocal

__all__ = ['ExecuteLocal']
