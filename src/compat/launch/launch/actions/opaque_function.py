"""OpaqueFunction: call Python code when the action executes."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class OpaqueFunction(Action):
    """Call function(context, *args, **kwargs) at execution; visit the entities it returns."""

    def __init__(self, *, function: Callable[..., Iterable[LaunchDescriptionEntity] | None],
                 args: Iterable[Any] | None = None, kwargs: dict[str, Any] | None = None,
                 **action_kwargs: Any) -> None:
        super().__init__(**action_kwargs)
        if not callable(function):
            raise TypeError(f"OpaqueFunction expected a callable for 'function', got '{type(function)}'")
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> Iterable[LaunchDescriptionEntity] | None:
        return self.function(context, *self.args, **self.kwargs)
