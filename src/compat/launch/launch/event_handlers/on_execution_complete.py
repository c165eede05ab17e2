"""Upstream's module path; implemented in launch.event_handlers."""

from launch.event_handlers import OnExecutionComplete

__all__ = ['OnExecutionComplete']
