"""launch_ros: ROS-specific launch actions (compatible re-implementation for Owl Kit Lab)."""

from launch_ros import (
    actions,
    descriptions,
    event_handlers,
    events,
    parameter_descriptions,
    substitutions,
    utilities,
)

__all__ = [
    'actions', 'descriptions', 'event_handlers', 'events', 'parameter_descriptions', 'substitutions',
    'utilities',
]
