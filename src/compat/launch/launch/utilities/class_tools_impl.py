"""is_a, is_a_subclass and isclassinstance: isinstance checks by upstream's names."""

from __future__ import annotations

from typing import Any


def isclassinstance(obj: Any) -> bool:
    """Whether obj is an instance of some class: in Python 3 everything is, as upstream's check says."""
    return hasattr(obj, '__class__')


def is_a(obj: Any, entity_type: type | tuple[type, ...]) -> bool:
    """isinstance, named as upstream names it."""
    return isinstance(obj, entity_type)


def is_a_subclass(obj: Any, entity_type: type | tuple[type, ...]) -> bool:
    """Obj is an instance of entity_type, or a class derived from it."""
    if isinstance(obj, type):
        return issubclass(obj, entity_type)
    return isinstance(obj, entity_type)
