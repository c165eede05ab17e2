"""Upstream's older home of matches_node_name, kept as upstream keeps it: see launch_ros.events.matchers."""

from launch_ros.events.matchers import matches_node_name

__all__ = ['matches_node_name']
