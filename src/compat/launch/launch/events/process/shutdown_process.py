"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ShutdownProcess

__all__ = ['ShutdownProcess']
