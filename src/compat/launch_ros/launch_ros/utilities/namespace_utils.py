"""Namespaces: made absolute, and a relative one put under a base."""

from __future__ import annotations

from launch_ros.actions.node import join_namespaces, make_namespace_absolute

__all__ = ['is_root_namespace', 'make_namespace_absolute', 'prefix_namespace']


def is_root_namespace(namespace: str) -> bool:
    """Whether a namespace is the root one: '' or '/'."""
    return namespace in ('', '/')


def prefix_namespace(base_ns: str | None, namespace: str | None) -> str | None:
    """Namespace under base_ns unless namespace is absolute; None when both are None."""
    if namespace is None:
        return base_ns
    return join_namespaces(base_ns, namespace)
