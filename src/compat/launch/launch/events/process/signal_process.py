"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import SignalProcess

__all__ = ['SignalProcess']
