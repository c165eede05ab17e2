"""launch_ros: ROS-specific launch actions (compatible re-implementation for Owl Kit Lab)."""

from launch_ros import actions, parameter_descriptions, substitutions

__all__ = ['actions', 'parameter_descriptions', 'substitutions']
