"""OpaqueCoroutine: run an async function inside launch's event loop for as long as it takes."""

from __future__ import annotations

import asyncio
import inspect
from collections.abc import Callable, Coroutine, Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.event_handler import CallbackEventHandler
from launch.events.shutdown import Shutdown

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext


class OpaqueCoroutine(Action):
    """Await coroutine(context, *args, **kwargs) (without context if ignore_context) as a task.

    Launch stays up while the task runs; a shutdown cancels it.  What the coroutine returns is
    ignored (an OpaqueFunction is the way to return entities).  An exception in it is reported by
    launch like any other and shuts the launch down.
    """

    def __init__(self, *, coroutine: Callable[..., Coroutine[Any, Any, Any]],
                 args: Iterable[Any] | None = None, kwargs: dict[str, Any] | None = None,
                 ignore_context: bool = False, **action_kwargs: Any) -> None:
        super().__init__(**action_kwargs)
        if not inspect.iscoroutinefunction(coroutine):
            raise TypeError("OpaqueCoroutine expected an 'async def' function for 'coroutine', got "
                            f"'{type(coroutine).__name__}'")
        self.coroutine = coroutine
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})
        self.ignore_context = ignore_context
        self._task: asyncio.Task | None = None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._task

    def _cancel(self, _event: Event, _context: LaunchContext) -> None:
        if self._task is not None and not self._task.done():
            self._task.cancel()

    def execute(self, context: LaunchContext) -> None:
        arguments = self.args if self.ignore_context else [context, *self.args]
        context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, Shutdown), callback=self._cancel, handle_once=True))
        self._task = asyncio.get_running_loop().create_task(self.coroutine(*arguments, **self.kwargs))
