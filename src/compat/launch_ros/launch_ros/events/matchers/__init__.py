"""Matchers of ROS actions for events that target actions (ChangeState...)."""

from launch_ros.events.matchers.matches_node_name import matches_node_name

__all__ = ['matches_node_name']
