"""Registries of the frontend: which class a tag builds, which substitution a `$(name)` makes."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

# tag -> class with parse(entity, parser) -> (class, constructor kwargs)
action_parse_methods: dict[str, type] = {}
# name -> function(list of argument substitution lists) -> Substitution
substitution_parse_methods: dict[str, Callable[[list[list[Any]]], Any]] = {}


def expose_action(tag: str) -> Callable[[type], type]:
    """Class decorator: the frontend tag `tag` builds this action through its parse classmethod."""
    def register(cls: type) -> type:
        action_parse_methods[tag] = cls
        return cls
    return register


def expose_substitution(name: str, min_args: int = 0, max_args: int | None = None
                        ) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Function decorator: `$(name arg...)` calls it with the arguments' substitution lists."""
    def register(function: Callable[..., Any]) -> Callable[..., Any]:
        def checked(args: list[list[Any]]) -> Any:
            upper = min_args if max_args is None else max_args
            if not min_args <= len(args) <= upper:
                expected = str(min_args) if upper == min_args else f'{min_args} to {upper}'
                raise ValueError(f"substitution '{name}' expects {expected} argument(s), got {len(args)}")
            return function(*args)
        substitution_parse_methods[name] = checked
        return function
    return register
