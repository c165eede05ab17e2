"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessExited

__all__ = ['ProcessExited']
