"""Namespaces: made absolute, and a relative one put under a base."""

from __future__ import annotations

__all__ = ['is_root_namespace', 'join_namespaces', 'make_namespace_absolute', 'prefix_namespace']


def is_root_namespace(namespace: str) -> bool:
    """Whether a namespace is the root one: '' or '/'."""
    return namespace in ('', '/')


def make_namespace_absolute(namespace: str) -> str:
    """The namespace with exactly one leading '/' and no trailing one; '/' for an empty one."""
    namespace = '/' + namespace.strip('/') if namespace.strip('/') else '/'
    return namespace


def join_namespaces(base: str | None, namespace: str) -> str:
    """A relative namespace goes under the pushed one; an absolute one replaces it."""
    if namespace.startswith('/') or not base:
        return namespace
    return base.rstrip('/') + '/' + namespace


def prefix_namespace(base_ns: str | None, namespace: str | None) -> str | None:
    """Namespace under base_ns unless namespace is absolute; None when both are None."""
    if namespace is None:
        return base_ns
    return join_namespaces(base_ns, namespace)
