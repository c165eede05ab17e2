"""Upstream's module path; implemented in launch.events."""

from launch.events import Shutdown

__all__ = ['Shutdown']
