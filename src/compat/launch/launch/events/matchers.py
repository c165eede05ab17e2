"""matches_action: a matcher of the events about one action."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.action import Action


def matches_action(target_action: Action) -> Callable[[Action], bool]:
    """A matcher for process events and process-targeting events of exactly this action."""
    return lambda action: action is target_action
