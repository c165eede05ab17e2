"""ComposableNodeContainer, LoadComposableNodes: refused, each in one clear line.

Composable nodes are C++ classes loaded into a container process (rclcpp_components); the pinned
Python wheels ship no rclcpp_components and no container executable, so nothing could load them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NoReturn

from launch.action import Action
from launch.frontend.expose import expose_action

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser

COMPOSITION_UNAVAILABLE = (
    '{what} is not available here: composable nodes are C++ components loaded by rclcpp_components, '
    'which the Python ROS 2 wheels do not include; start each node as its own launch_ros.actions.Node')


class CompositionUnavailableError(RuntimeError):
    """Raised at construction, so a launch file fails before anything starts."""


def _refuse(what: str) -> NoReturn:
    raise CompositionUnavailableError(COMPOSITION_UNAVAILABLE.format(what=what))


@expose_action('node_container')
class ComposableNodeContainer(Action):
    """Upstream's container of composable nodes: refused when constructed, with the reason and what to use."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        _refuse('ComposableNodeContainer')

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Refuse a <node_container> tag, in the file's own error, before anything starts."""
        raise entity.error(COMPOSITION_UNAVAILABLE.format(what='<node_container>'))


@expose_action('load_composable_node')
class LoadComposableNodes(Action):
    """Upstream's action that loads composable nodes into a container: refused like the container."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        _refuse('LoadComposableNodes')

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Refuse a <load_composable_node> tag, in the file's own error, before anything starts."""
        raise entity.error(COMPOSITION_UNAVAILABLE.format(what='<load_composable_node>'))


class ComposableNode:
    """The description of a component: refused like the actions that would load it."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        _refuse('ComposableNode')
