"""Upstream's module path; implemented in launch.event_handlers."""

from launch.event_handlers import OnProcessIO

__all__ = ['OnProcessIO']
