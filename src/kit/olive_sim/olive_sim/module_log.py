"""A module's own log for its Log Monitor page: the lines its node logs, kept in a ring.

Every line the node logs (what it also sends to /rosout and prints) is kept, and handed to whoever
listens as it comes.

Kept in the module's process (no /rosout subscription: that would take every node's lines over
DDS to keep only ours). A restart empties it, as a reboot empties a device's log.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from typing import Any

KEPT_LINES = 500
LEVELS = ('debug', 'info', 'warning', 'error', 'fatal')


class LogBook:
    """The last KEPT_LINES lines; listeners get each new line (from the logging thread: be quick)."""

    def __init__(self, kept: int = KEPT_LINES, clock: Callable[[], float] = time.time) -> None:
        self._lines: deque[dict[str, Any]] = deque(maxlen=kept)
        self._listeners: list[Callable[[dict[str, Any]], None]] = []
        self._lock = threading.Lock()
        self._clock = clock
        self._count = 0

    def add(self, level: str, message: str) -> None:
        """Keep a line, numbered and timed, and hand it to every listener on the caller's thread."""
        with self._lock:
            self._count += 1
            line = {'n': self._count, 'time': self._clock(), 'level': level, 'message': message}
            self._lines.append(line)
            listeners = list(self._listeners)
        for listener in listeners:
            listener(line)

    def lines(self) -> list[dict[str, Any]]:
        """The kept lines, oldest first, each a dict of n, time, level and message."""
        with self._lock:
            return list(self._lines)

    def listen(self, listener: Callable[[dict[str, Any]], None]) -> list[dict[str, Any]]:
        """Add a listener; returns the lines so far (none is missed or sent twice in between)."""
        with self._lock:
            self._listeners.append(listener)
            return list(self._lines)

    def forget(self, listener: Callable[[dict[str, Any]], None]) -> None:
        """Remove a listener (one not listening is ignored)."""
        with self._lock:
            if listener in self._listeners:
                self._listeners.remove(listener)


class RecordingLogger:
    """A node's rclpy logger that also writes each line it emits into a LogBook.

    Everything else (get_child, set_level, ...) is the rclpy logger's own. Only the severity
    methods are recorded, with the message as given (rclpy adds the node's name and time).
    """

    def __init__(self, logger: Any, book: LogBook) -> None:
        self._logger = logger
        self._book = book

    def __getattr__(self, name: str) -> Any:
        return getattr(self._logger, name)

    # Each severity calls rclpy from a line of its own: rclpy keeps a context per calling line and
    # refuses a second severity from the same line.
    def _record(self, level: str, message: Any, logged: bool) -> bool:
        if logged:
            self._book.add(level, str(message))
        return logged

    def debug(self, message: Any, **kwargs: Any) -> bool:
        """Log at debug level through rclpy and record the line if rclpy logged it; True if it did."""
        return self._record('debug', message, self._logger.debug(message, **kwargs))

    def info(self, message: Any, **kwargs: Any) -> bool:
        """Log at info level through rclpy and record the line if rclpy logged it; True if it did."""
        return self._record('info', message, self._logger.info(message, **kwargs))

    def warning(self, message: Any, **kwargs: Any) -> bool:
        """Log at warning level through rclpy and record the line if rclpy logged it; True if it did."""
        return self._record('warning', message, self._logger.warning(message, **kwargs))

    def warn(self, message: Any, **kwargs: Any) -> bool:
        """The old name of warning, kept as rclpy keeps it: logged and recorded at warning level."""
        return self._record('warning', message, self._logger.warning(message, **kwargs))

    def error(self, message: Any, **kwargs: Any) -> bool:
        """Log at error level through rclpy and record the line if rclpy logged it; True if it did."""
        return self._record('error', message, self._logger.error(message, **kwargs))

    def fatal(self, message: Any, **kwargs: Any) -> bool:
        """Log at fatal level through rclpy and record the line if rclpy logged it; True if it did."""
        return self._record('fatal', message, self._logger.fatal(message, **kwargs))
