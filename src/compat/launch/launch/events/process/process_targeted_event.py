"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessTargetedEvent

__all__ = ['ProcessTargetedEvent']
