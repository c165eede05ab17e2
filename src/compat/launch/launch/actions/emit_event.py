"""Upstream's module path; implemented in launch.actions.event_actions."""

from launch.actions.event_actions import EmitEvent

__all__ = ['EmitEvent']
