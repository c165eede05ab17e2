"""ensure_argument_type: a TypeError naming the argument and its caller."""

from __future__ import annotations

from typing import Any


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
