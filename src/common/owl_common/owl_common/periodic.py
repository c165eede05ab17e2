"""A callback at a fixed rate on a thread of its own, for a node's high-rate work."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

# s: shorter delays are slept with time.sleep, which costs a third less CPU per wake-up than
# Event.wait; a stop request then waits at most this long.
SLEEP_LIMIT = 0.1

_call = threading.local()  # the call under way on a PeriodicThread's thread


def scheduled_time() -> float:
    """The time.monotonic() at which the periodic call under way on this thread was due.

    A sensor takes its sample at this time and stamps it with it: a machine that holds the thread
    up delays the message, not the sample, as with a real sensor's own clock. Only valid inside a
    PeriodicThread's callback.
    """
    return _call.due


# ns: a wall-clock reading bracketed by monotonic readings further apart than this was held up by
# the machine (preempted, or another thread took the GIL) and is read again
CLOCK_BRACKET = 50_000
CLOCK_ATTEMPTS = 5


def wall_time_ns(monotonic: float) -> int:
    """The system clock's time in ns at an instant given as time.monotonic(), e.g. a sample's due time.

    The offset between the two clocks is read with the wall clock between two monotonic readings:
    two plain readings in a row are skewed by however long the thread is held up between them
    (a busy machine once moved a 100 Hz stamp 2.9 ms off its grid). The narrowest bracket of a few
    tries is used.
    """
    best_width, offset = None, 0
    for _ in range(CLOCK_ATTEMPTS):
        before = time.monotonic_ns()
        wall = time.time_ns()
        after = time.monotonic_ns()
        if best_width is None or after - before < best_width:
            best_width, offset = after - before, wall - (before + after) // 2
        if best_width <= CLOCK_BRACKET:
            break
    return offset + round(monotonic * 1e9)


def next_call(last_due: float, now: float, period: float, catch_up: float) -> tuple[float, float]:
    """The next call's due time after the one due at last_due, and how long to wait for it.

    A wait <= 0 means call at once. The schedule does not drift; calls the thread missed while the
    machine held it up are made up back to back while they are at most catch_up (and always one
    period) late, so a 100 Hz sensor still gives 100 samples a second; further behind, the schedule
    restarts now.
    """
    due = last_due + period
    if now - due > max(period, catch_up):
        return now, 0.0
    return due, due - now


class PeriodicThread:
    """Calls `callback` at a fixed rate on its own thread, on a schedule that does not drift.

    High-rate work (100 Hz sensors, 30 fps images, turtlesim's 62.5 Hz tick) runs here rather
    than on executor timers: each executor wake-up costs the whole wait set of the node (parameter
    services, every QoS event handler and all), which multiplied the nodes' CPU use. `finish`, if
    given, runs on the thread after the last call, for what must be closed where it was used.
    `skipped`, if given, is told (calls skipped, s the schedule jumped) each time the machine held
    the thread up longer than catch_up and the schedule restarted, so a sensor can say why its
    stamps have a gap.
    """

    def __init__(self, rate: float, callback: Callable[[], None], name: str,
                 alive: Callable[[], bool], finish: Callable[[], None] | None = None,
                 catch_up: float = 0.0, skipped: Callable[[int, float], None] | None = None) -> None:
        self.period = 1.0 / rate
        self.catch_up = catch_up
        self.skipped = skipped
        self.callback = callback
        self.alive = alive
        self.finish = finish
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            self._loop()
        finally:
            if self.finish is not None:
                self.finish()

    def _loop(self) -> None:
        due = time.monotonic()
        while not self._stop.is_set():
            last_due = due
            due, delay = next_call(due, time.monotonic(), self.period, self.catch_up)
            if self.skipped is not None and due - last_due > 1.5 * self.period:
                self.skipped(round((due - last_due) / self.period) - 1, due - last_due)
            if 0 < delay <= SLEEP_LIMIT:
                time.sleep(delay)
                if self._stop.is_set():
                    return
            elif delay > 0 and self._stop.wait(delay):
                return
            _call.due = due
            try:
                self.callback()
            except Exception:
                if self._stop.is_set() or not self.alive():
                    return  # Ctrl-C shut ROS down, or the node is being destroyed, under the callback
                raise

    def stop(self) -> None:
        """Stop calling; waits (up to 2 s) for a call under way and `finish` to end."""
        self._stop.set()
        if self._thread is not threading.current_thread():
            self._thread.join(2.0)
