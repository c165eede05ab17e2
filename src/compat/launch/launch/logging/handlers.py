"""Logging handlers that can give each logger a format of its own.

Launch shares one screen handler and one launch.log handler between its own loggers and the
output loggers of processes: a process's lines are written as they are, while launch's records
get `[LEVEL] [name]:`. Every handler class of `logging` and `logging.handlers` is available here
under its usual name with that ability (`launch.logging.handlers.RotatingFileHandler` ...).
"""

from __future__ import annotations

import logging
import logging.handlers
from typing import Any, cast

__all__ = ['FileHandler', 'Handler', 'NullHandler', 'StreamHandler', 'WatchedFileHandler',
           'with_per_logger_formatting']


class Handler(logging.Handler):
    """A handler whose records from chosen loggers use a formatter of their own."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._formatters: dict[str, logging.Formatter] = {}

    def setFormatterFor(self, logger: logging.Logger | str, formatter: logging.Formatter) -> None:
        """Format the records of `logger` (a logger or its name) with `formatter`."""
        self._formatters[logger if isinstance(logger, str) else logger.name] = formatter

    def unsetFormatterFor(self, logger: logging.Logger | str) -> None:
        """Back to the handler's own formatter for `logger`; nothing happens if it had none."""
        self._formatters.pop(logger if isinstance(logger, str) else logger.name, None)

    def format(self, record: logging.LogRecord) -> str:
        formatter = self._formatters.get(record.name)
        return formatter.format(record) if formatter is not None else super().format(record)


def with_per_logger_formatting(cls: type[logging.Handler]) -> type[Handler]:
    """`cls` with `setFormatterFor`/`unsetFormatterFor` added (`cls` itself if it has them)."""
    if issubclass(cls, Handler):
        return cls
    namespace = {'__doc__': cls.__doc__, '__module__': __name__, '__qualname__': cls.__name__}
    return cast(type[Handler], type(cls.__name__, (Handler, cls), namespace))


# The handlers launch itself builds, spelled out so that type checkers know them.
class StreamHandler(Handler, logging.StreamHandler):
    """logging.StreamHandler with per-logger formatting."""


class FileHandler(Handler, logging.FileHandler):
    """logging.FileHandler with per-logger formatting."""


class WatchedFileHandler(Handler, logging.handlers.WatchedFileHandler):
    """logging.handlers.WatchedFileHandler with per-logger formatting."""


class NullHandler(Handler, logging.NullHandler):
    """logging.NullHandler with per-logger formatting."""


_made: dict[str, type[Handler]] = {}


def __getattr__(name: str) -> Any:
    """The other handler classes, made on first use; other names of logging.handlers as they are."""
    if name in _made:
        return _made[name]
    for module in (logging, logging.handlers):
        found = getattr(module, name, None)
        if not name.startswith('_') and isinstance(found, type) and issubclass(found, logging.Handler):
            _made[name] = with_per_logger_formatting(found)
            return _made[name]
    if hasattr(logging.handlers, name):
        return getattr(logging.handlers, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
