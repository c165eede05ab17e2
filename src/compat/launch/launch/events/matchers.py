"""Upstream's module path; implemented in launch.events."""

from launch.events import matches_action

__all__ = ['matches_action']
