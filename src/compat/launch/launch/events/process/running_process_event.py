"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import RunningProcessEvent

__all__ = ['RunningProcessEvent']
