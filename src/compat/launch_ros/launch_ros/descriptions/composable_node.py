"""ComposableNode: refused, as every piece of composition is, in one clear line.

Composable nodes are C++ classes loaded into a container process (rclcpp_components); the pinned
Python wheels ship no rclcpp_components and no container executable, so nothing could load them.
ComposableNodeContainer and LoadComposableNodes raise the same error with the same message.
"""

from __future__ import annotations

from typing import Any

COMPOSITION_UNAVAILABLE = (
    '{what} is not available here: composable nodes are C++ components loaded by rclcpp_components, '
    'which the Python ROS 2 wheels do not include; start each node as its own launch_ros.actions.Node')


class CompositionUnavailableError(RuntimeError):
    """Raised at construction, so a launch file fails before anything starts."""


class ComposableNode:
    """The description of a component: refused like the actions that would load it."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise CompositionUnavailableError(COMPOSITION_UNAVAILABLE.format(what='ComposableNode'))
