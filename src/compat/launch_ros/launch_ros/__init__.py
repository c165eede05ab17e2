"""launch_ros: ROS-specific launch actions (compatible re-implementation for Owl Kit Lab).

Importing the package imports its actions and substitutions, which registers their XML/YAML tags and
`$(...)` names. setup.py declares the package in the `launch.frontend.launch_extension` entry-point
group, the group through which upstream's launch frontend finds its extensions.
"""

from launch_ros import (
    actions,
    descriptions,
    event_handlers,
    events,
    parameter_descriptions,
    ros_adapters,
    substitutions,
    utilities,
)

__all__ = [
    'actions', 'descriptions', 'event_handlers', 'events', 'parameter_descriptions', 'ros_adapters',
    'substitutions', 'utilities',
]
