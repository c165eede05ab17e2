"""LoadComposableNodes and its LoadNode request builder: refused in one clear line (see ComposableNode)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action

from launch_ros.descriptions.composable_node import COMPOSITION_UNAVAILABLE, CompositionUnavailableError

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext

# Why the request cannot even be built: its message package is not installed, not only the containers.
LOAD_REQUEST_UNAVAILABLE = (
    'get_composable_node_load_request is not available here: it builds a '
    'composition_interfaces.srv.LoadNode request, and composition_interfaces is not among the installed '
    'ROS 2 Python packages (nor is rclcpp_components, whose containers answer that request)')


@expose_action('load_composable_node')
class LoadComposableNodes(Action):
    """Upstream's action that loads composable nodes into a container: refused like the container."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise CompositionUnavailableError(COMPOSITION_UNAVAILABLE.format(what='LoadComposableNodes'))

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Refuse a <load_composable_node> tag, in the file's own error, before anything starts."""
        raise entity.error(COMPOSITION_UNAVAILABLE.format(what='<load_composable_node>'))


def get_composable_node_load_request(composable_node_description: Any, context: LaunchContext) -> Any:
    """Upstream's LoadNode request for a ComposableNode: refused, see LOAD_REQUEST_UNAVAILABLE."""
    raise CompositionUnavailableError(LOAD_REQUEST_UNAVAILABLE)
