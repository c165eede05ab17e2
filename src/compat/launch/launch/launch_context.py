"""The state a launch runs in: configurations, environment, locals, event handlers, event queue."""

from __future__ import annotations

import asyncio
import collections
import os
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from launch.event import Event
    from launch.event_handler import BaseEventHandler
    from launch.substitution import Substitution


class _Locals:
    """Attribute view of the merged locals frames: context.locals.event, ...current_launch_file_path."""

    def __init__(self, frames: list[dict[str, Any]]) -> None:
        self._frames = frames

    def __getattr__(self, name: str) -> Any:
        for frame in reversed(self._frames):
            if name in frame:
                return frame[name]
        raise AttributeError(f"context.locals does not contain attribute '{name}', it contains: "
                             f'[{", ".join(sorted({k for f in self._frames for k in f}))}]')


class LaunchContext:
    """Runtime context of a launch, shared by every action and substitution."""

    def __init__(self, *, argv: Iterable[str] | None = None, noninteractive: bool = False) -> None:
        self.argv = list(argv or [])
        self.noninteractive = noninteractive
        self.launch_configurations: dict[str, Any] = {}
        self._configurations_stack: list[dict[str, Any]] = []
        self._initial_environment = dict(os.environ)
        self._environment_stack: list[dict[str, str]] = []
        self._locals_frames: list[dict[str, Any]] = [{}]
        self._event_handlers: list[BaseEventHandler] = []
        self._event_queue: collections.deque[Event] = collections.deque()
        self._wakeup: asyncio.Event | None = None
        self._asyncio_loop: asyncio.AbstractEventLoop | None = None
        self._is_shutdown = False
        self._node_names: dict[str, int] = {}
        # Work launch waits for besides the visited entities' futures (add_completion_future).
        self._completion_futures: list[asyncio.Future] = []
        # Every ExecuteProcess that ran, so that nothing outlives a cancelled launch.
        self._process_actions: list[Any] = []

    # Environment: the launch process's own os.environ, as upstream.
    @property
    def environment(self) -> os._Environ:
        return os.environ

    def _set_environment(self, values: dict[str, str]) -> None:
        os.environ.clear()
        os.environ.update(values)

    def _push_environment(self) -> None:
        self._environment_stack.append(dict(os.environ))

    def _pop_environment(self) -> None:
        self._set_environment(self._environment_stack.pop())

    def _reset_environment(self) -> None:
        self._set_environment(self._initial_environment)

    # Launch configurations: a flat dict; groups push and pop copies.
    def _push_launch_configurations(self) -> None:
        self._configurations_stack.append(dict(self.launch_configurations))

    def _pop_launch_configurations(self) -> None:
        self.launch_configurations = self._configurations_stack.pop()

    # Locals: scratch values of the entities being visited (event, current launch file...).
    @property
    def locals(self) -> _Locals:
        return _Locals(self._locals_frames)

    def extend_locals(self, values: dict[str, Any]) -> None:
        self._locals_frames[-1].update(values)

    def _push_locals(self) -> None:
        self._locals_frames.append({})

    def _pop_locals(self) -> None:
        self._locals_frames.pop()

    def get_locals_as_dict(self) -> dict[str, Any]:
        merged: dict[str, Any] = {}
        for frame in self._locals_frames:
            merged.update(frame)
        return merged

    # Event handlers: the newest is matched first unless appended.
    def register_event_handler(self, event_handler: BaseEventHandler, append: bool = False) -> None:
        if append:
            self._event_handlers.append(event_handler)
        else:
            self._event_handlers.insert(0, event_handler)

    def unregister_event_handler(self, event_handler: BaseEventHandler) -> None:
        try:
            self._event_handlers.remove(event_handler)
        except ValueError:
            raise ValueError('event handler is not registered') from None

    def would_handle_event(self, event: Event) -> bool:
        return any(handler.matches(event) for handler in self._event_handlers)

    def emit_event_sync(self, event: Event) -> None:
        self._event_queue.append(event)
        if self._wakeup is not None:
            self._wakeup.set()

    async def emit_event(self, event: Event) -> None:
        self.emit_event_sync(event)

    def perform_substitution(self, substitution: Substitution) -> str:
        """The text of one substitution in this context."""
        return substitution.perform(self)

    def add_completion_future(self, completion_future: asyncio.Future) -> None:
        """Keep launch running until this future is done (e.g. a service call in a thread)."""
        self._completion_futures.append(completion_future)
        if self._wakeup is not None:
            self._wakeup.set()

    @property
    def is_shutdown(self) -> bool:
        return self._is_shutdown

    @property
    def asyncio_loop(self) -> asyncio.AbstractEventLoop | None:
        return self._asyncio_loop
