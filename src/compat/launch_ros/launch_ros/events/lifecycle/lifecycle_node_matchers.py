"""Upstream's module path; implemented in launch_ros.events.matchers."""

from launch_ros.events.matchers import matches_node_name

__all__ = ['matches_node_name']
