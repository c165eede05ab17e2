"""How many nodes of each fully qualified name this launch started (a duplicate gets a warning)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['add_node_name', 'get_node_name_count']


def add_node_name(context: LaunchContext, node_name: str) -> None:
    """Count one more node started with this fully qualified name in this launch."""
    context._node_names[node_name] = context._node_names.get(node_name, 0) + 1


def get_node_name_count(context: LaunchContext, node_name: str) -> int:
    """How many nodes with this fully qualified name this launch has started so far."""
    return context._node_names.get(node_name, 0)
