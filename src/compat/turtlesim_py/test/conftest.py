"""Fixtures of turtlesim's node-free unit tests."""

from __future__ import annotations

from collections.abc import Callable

import pytest
from turtlesim_py import world
from turtlesim_py.turtle import Turtle


class RecordingLogger:
    """Stands in for the node's logger: keeps (level, text) pairs."""

    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []

    def info(self, message: str) -> None:
        self.lines.append(('INFO', message))

    def warning(self, message: str) -> None:
        self.lines.append(('WARN', message))

    def texts(self, level: str) -> list[str]:
        return [text for lvl, text in self.lines if lvl == level]


@pytest.fixture
def new_turtle() -> Callable[..., Turtle]:
    """Factory: a turtle1 at world (x, y, theta), its logger a RecordingLogger, time 0."""
    def make(x: float = world.CENTER, y: float = world.CENTER, theta: float = 0.0) -> Turtle:
        return Turtle.spawn('turtle1', x, y, theta, now=0.0, logger=RecordingLogger())
    return make
