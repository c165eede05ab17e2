"""ComposableNodeContainer: refused in one clear line (see launch_ros.descriptions.composable_node)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action

from launch_ros.descriptions.composable_node import COMPOSITION_UNAVAILABLE, CompositionUnavailableError

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser


@expose_action('node_container')
class ComposableNodeContainer(Action):
    """Upstream's container of composable nodes: refused when constructed, with the reason and what to use."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        raise CompositionUnavailableError(COMPOSITION_UNAVAILABLE.format(what='ComposableNodeContainer'))

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Refuse a <node_container> tag, in the file's own error, before anything starts."""
        raise entity.error(COMPOSITION_UNAVAILABLE.format(what='<node_container>'))
