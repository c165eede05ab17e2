"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessIO

__all__ = ['ProcessIO']
