"""The read-only QoS parameters an rclcpp node shows for its /parameter_events publisher.

Upstream's nodes are C++, so `ros2 param list/dump` of them (as the course prints it) includes
qos_overrides./parameter_events.publisher.{depth,durability,history,reliability}. rclpy has no
such parameters; we declare them read-only with the QoS this node really publishes with.
"""

from __future__ import annotations

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node
from rclpy.qos import qos_profile_parameter_events

PREFIX = 'qos_overrides./parameter_events.publisher.'


def declare_parameter_events_qos(node: Node) -> None:
    """Declare the four read-only qos_overrides./parameter_events.publisher.* parameters on the node."""
    profile = qos_profile_parameter_events
    values = {
        'depth': profile.depth,
        'durability': profile.durability.name.lower(),
        'history': profile.history.name.lower(),
        'reliability': profile.reliability.name.lower(),
    }
    for policy, value in values.items():
        # A --params-file (e.g. a `ros2 param dump`) cannot change them: they report, not configure.
        node.declare_parameter(PREFIX + policy, value, ParameterDescriptor(
            description=f'{policy} of the /parameter_events publisher', read_only=True),
            ignore_override=True)
