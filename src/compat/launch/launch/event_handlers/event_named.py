"""event_named: a matcher of events by their `name` (e.g. 'launch.events.Shutdown')."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ['event_named']


def event_named(name: str) -> Callable[[Any], bool]:
    return lambda event: getattr(event, 'name', None) == name
