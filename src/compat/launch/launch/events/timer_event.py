"""Upstream's module path; implemented in launch.events."""

from launch.events import TimerEvent

__all__ = ['TimerEvent']
