"""Upstream's module path; implemented in launch.events."""

from launch.events import ExecutionComplete

__all__ = ['ExecutionComplete']
