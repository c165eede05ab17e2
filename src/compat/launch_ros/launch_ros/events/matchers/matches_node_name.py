"""matches_node_name: a matcher of the Node action with a given name, for events that target actions."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ['matches_node_name']


def matches_node_name(node_name: str) -> Callable[[Any], bool]:
    """A matcher of the Node action whose fully qualified name is node_name ('/' is added in front)."""
    if not node_name.startswith('/'):
        node_name = '/' + node_name
    return lambda action: getattr(action, 'node_name', None) == node_name
