"""create_future: a future of an event loop."""

from __future__ import annotations

import asyncio


def create_future(loop: asyncio.AbstractEventLoop | None = None) -> asyncio.Future:
    """A future of the running loop (or of loop)."""
    return (loop or asyncio.get_event_loop()).create_future()
