"""The base class of conditions: whether an action executes."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class Condition:
    """Wraps a predicate `context -> bool`, evaluated when the action is visited.

    Without a predicate a condition is false, as upstream's is: an action given a bare
    Condition() never executes.
    """

    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._predicate = predicate

    def evaluate(self, context: LaunchContext) -> bool:
        return False if self._predicate is None else bool(self._predicate(context))

    def describe(self) -> str:
        return type(self).__name__
