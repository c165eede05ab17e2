"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import ProcessStarted

__all__ = ['ProcessStarted']
