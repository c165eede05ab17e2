"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessStdout

__all__ = ['ProcessStdout']
