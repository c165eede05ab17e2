"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessStdin

__all__ = ['ProcessStdin']
