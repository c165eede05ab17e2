"""Namespaces: which are absolute or the root, a relative one put under a base, made absolute."""

from __future__ import annotations

from typing import overload

__all__ = ['is_namespace_absolute', 'is_root_namespace', 'make_namespace_absolute', 'prefix_namespace']


def is_root_namespace(ns: str) -> bool:
    """Whether ns is exactly '/' (an empty namespace is not the root one until made absolute)."""
    return ns == '/'


def is_namespace_absolute(ns: str) -> bool:
    """Whether ns starts with '/'."""
    return ns.startswith('/')


@overload
def prefix_namespace(base_ns: str | None, ns: str) -> str: ...
@overload
def prefix_namespace(base_ns: str | None, ns: str | None) -> str | None: ...


def prefix_namespace(base_ns: str | None, ns: str | None) -> str | None:
    """The namespace ns under base_ns when ns is relative; ns itself when absolute or without a base.

    None when both are None, base_ns when only ns is None. Trailing '/' are removed from the result,
    except from the root namespace '/'.
    """
    if ns is None:
        combined = base_ns
    elif not base_ns or is_namespace_absolute(ns):
        combined = ns
    else:
        combined = ('' if is_root_namespace(base_ns) else base_ns) + '/' + ns
    if combined is None or is_root_namespace(combined):
        return combined
    return combined.rstrip('/')


@overload
def make_namespace_absolute(ns: str) -> str: ...
@overload
def make_namespace_absolute(ns: str | None) -> str | None: ...


def make_namespace_absolute(ns: str | None) -> str | None:
    """The namespace with a leading '/' added when it has none; None stays None."""
    if ns is None or is_namespace_absolute(ns):
        return ns
    return '/' + ns
