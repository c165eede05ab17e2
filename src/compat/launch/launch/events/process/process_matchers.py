"""Upstream's module path; implemented in launch.events.process."""

from launch.events.process import matches_executable, matches_name, matches_pid

__all__ = ['matches_executable', 'matches_name', 'matches_pid']
