"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessStderr

__all__ = ['ProcessStderr']
