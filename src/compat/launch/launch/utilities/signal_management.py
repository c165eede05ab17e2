"""Signal handlers that run inside an asyncio loop, for the length of a `with` block."""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from types import TracebackType

SignalHandler = Callable[[int], None]


class AsyncSafeSignalManager:
    """Runs signal handlers between the loop's callbacks, where they may touch anything.

    handle(signum, handler) sets the handler of a signal (None takes it away) and returns the one
    it replaces; leaving the `with` block takes away every handler set through it. Handlers are
    called with the signal number. As asyncio's own signal handling, it works in the main thread
    only: elsewhere handle() raises ValueError.
    """

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        self._loop = loop
        self._handlers: dict[int, SignalHandler] = {}

    def __enter__(self) -> AsyncSafeSignalManager:
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc_value: BaseException | None,
                 exc_traceback: TracebackType | None) -> None:
        for signum in list(self._handlers):
            self.handle(signum, None)

    def handle(self, signum: int, handler: SignalHandler | None) -> SignalHandler | None:
        """Set (or, with None, take away) the handler of signum; the handler it had before."""
        if handler is not None:
            try:
                self._loop.add_signal_handler(signum, handler, signum)
            except RuntimeError as error:  # asyncio's word for "not the main thread" on some paths
                raise ValueError(f'signal handlers can only be set in the main thread: {error}') from None
        elif signum in self._handlers:
            self._loop.remove_signal_handler(signum)
        previous = self._handlers.pop(signum, None)
        if handler is not None:
            self._handlers[signum] = handler
        return previous
