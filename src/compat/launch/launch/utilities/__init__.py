"""Helpers third-party launch code imports from upstream's launch.utilities."""

from __future__ import annotations

import asyncio
from typing import Any

from launch.substitution import (
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from launch.utilities import type_utils

__all__ = [
    'create_future', 'ensure_argument_type', 'is_a', 'is_a_subclass', 'normalize_to_list_of_substitutions',
    'perform_substitutions', 'type_utils',
]


def is_a(obj: Any, entity_type: type | tuple[type, ...]) -> bool:
    """isinstance, named as upstream names it."""
    return isinstance(obj, entity_type)


def is_a_subclass(obj: Any, entity_type: type | tuple[type, ...]) -> bool:
    """Obj is an instance of entity_type, or a class derived from it."""
    if isinstance(obj, type):
        return issubclass(obj, entity_type)
    return isinstance(obj, entity_type)


def ensure_argument_type(argument: Any, types: type | tuple[type, ...] | list[type],
                         argument_name: str, caller: str | None = None) -> None:
    """TypeError naming the argument and the caller when argument is none of types."""
    accepted = tuple(types) if isinstance(types, list) else types
    if isinstance(argument, accepted):
        return
    names = [t.__name__ for t in (accepted if isinstance(accepted, tuple) else (accepted,))]
    where = f" of '{caller}'" if caller else ''
    raise TypeError(f"Expected '{argument_name}'{where} to be one of {names}, got "
                    f"'{type(argument).__name__}'")


def create_future(loop: asyncio.AbstractEventLoop | None = None) -> asyncio.Future:
    """A future of the running loop (or of loop)."""
    return (loop or asyncio.get_event_loop()).create_future()
