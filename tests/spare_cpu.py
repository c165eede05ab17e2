"""Whether the machine has CPU to spare lately: the share of its cores' time spent idle, from /proc/stat.

conftest.py lets one more system test start than the machine's slots while the machine idles (tests
that wait on discovery, timers and deadlines leave a fast machine a third idle), never on a machine
the suite already keeps busy.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from pathlib import Path

PROC_STAT = Path('/proc/stat')
WINDOW = 2.0  # s: how far back "lately" reaches; a waiting test looks that long before it takes a spare slot


def cpu_times(proc_stat: str) -> tuple[int, int]:
    """(idle, total) clock ticks of all cores since boot, from the text of /proc/stat.

    Idle counts iowait too; total is user, nice, system, idle, iowait, irq, softirq and steal (guest
    time is inside user and nice already).
    """
    line = proc_stat.split('\n', 1)[0]
    first = line.split()
    if not first or first[0] != 'cpu':
        raise ValueError(f'not /proc/stat: its first line is {line[:60]!r}')
    ticks = [int(value) for value in first[1:9]]
    return ticks[3] + ticks[4], sum(ticks)


class IdleWatch:
    """The machine's idle share over the last WINDOW s, from samples taken each time it is asked."""

    def __init__(self, read: Callable[[], str] = PROC_STAT.read_text,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self._read = read
        self._clock = clock
        self._samples: deque[tuple[float, int, int]] = deque()

    def idle_share(self) -> float | None:
        """Idle ticks / all ticks since the newest sample at least WINDOW old; None until there is one."""
        now = self._clock()
        idle, total = cpu_times(self._read())
        self._samples.append((now, idle, total))
        while len(self._samples) > 1 and self._samples[1][0] <= now - WINDOW:
            self._samples.popleft()
        then, idle_then, total_then = self._samples[0]
        if then > now - WINDOW or total == total_then:
            return None
        return (idle - idle_then) / (total - total_then)


class IdleSampler:
    """An IdleWatch asked every PERIOD s by a thread of its own, from the sampler's making on.

    A test waiting for a spare slot then knows the last WINDOW's idle share at once, instead of
    watching the machine for a WINDOW first: those watches, one test at a time, had let at most one
    spare test start every WINDOW, and most system tests take less.
    """

    PERIOD = 0.1  # s

    def __init__(self, watch: IdleWatch | None = None) -> None:
        self._watch = watch or IdleWatch()
        self._share: float | None = None
        threading.Thread(target=self._sample, name='idle sampler', daemon=True).start()

    def share(self) -> float | None:
        """The idle share over the last WINDOW; None for the first WINDOW of the sampler's life."""
        return self._share

    def _sample(self) -> None:
        while True:
            self._share = self._watch.idle_share()
            time.sleep(self.PERIOD)
