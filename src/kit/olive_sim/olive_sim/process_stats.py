"""What a module's System Status page charts: its process's CPU and memory, and its traffic.

The traffic is the bytes of the ROS messages the module sends and takes.

The real module charts its whole board; a simulated module is one process on the student's PC, so
its charts are that process's. On one machine DDS carries the messages through shared memory, not
a network interface, so no interface counter sees them: the module counts the bytes it publishes
(Tx) and takes (Rx) itself, which is what the real module's Ethernet would carry.
Read from /proc and the process's CPU clock: no dependency, and nothing runs unless a page watches.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from dataclasses import dataclass


def process_cpu_seconds() -> float:
    """User + system CPU time of this process (every thread) in s.

    From the process's CPU clock, to the nanosecond: os.times() counts 10 ms ticks, so a module
    using under 1 % of a core charted 0 % in some seconds.
    """
    return time.process_time()


def resident_bytes(statm: str = '/proc/self/statm') -> int:
    """Resident memory of this process in bytes."""
    with open(statm, encoding='ascii') as stream:
        return int(stream.read().split()[1]) * os.sysconf('SC_PAGE_SIZE')


def total_memory_bytes() -> int:
    """The machine's physical memory in bytes."""
    return os.sysconf('SC_PHYS_PAGES') * os.sysconf('SC_PAGE_SIZE')


class ByteCounter:
    """Bytes counted by one thread only (so no lock: a reader sees a slightly old total)."""

    def __init__(self) -> None:
        self.sent = 0
        self.received = 0


class TrafficMeter:
    """The module's counters, one per thread that publishes or takes messages."""

    def __init__(self) -> None:
        self._counters: list[ByteCounter] = []

    def counter(self) -> ByteCounter:
        """A new counter, for one thread to add its bytes to; totals() includes it."""
        counter = ByteCounter()
        self._counters.append(counter)
        return counter

    def totals(self) -> tuple[int, int]:
        """(sent, received) bytes so far."""
        counters = list(self._counters)
        return sum(c.sent for c in counters), sum(c.received for c in counters)


@dataclass
class Sample:
    """One point of the System Status charts."""

    time: float          # s since the epoch, for the chart's axis
    cpu: float           # % of one core since the previous sample
    memory: float        # % of the machine's memory resident in this process
    memory_mb: float
    tx: float            # bytes/s sent since the previous sample
    rx: float            # bytes/s received


class ProcessSampler:
    """Samples of this process; the first call only sets the starting point (cpu, tx, rx are 0)."""

    def __init__(self, traffic: TrafficMeter, cpu_seconds: Callable[[], float] = process_cpu_seconds,
                 memory: Callable[[], int] = resident_bytes, total_memory: int | None = None,
                 clock: Callable[[], float] = time.monotonic, wall: Callable[[], float] = time.time) -> None:
        self.traffic = traffic
        self.cpu_seconds = cpu_seconds
        self.memory = memory
        self.total_memory = total_memory or total_memory_bytes()
        self.clock = clock
        self.wall = wall
        self._last: tuple[float, float, int, int] | None = None

    def sample(self) -> Sample:
        """The current sample: memory now, CPU and traffic as rates since the previous call."""
        now, cpu = self.clock(), self.cpu_seconds()
        sent, received = self.traffic.totals()
        resident = self.memory()
        last = self._last
        self._last = (now, cpu, sent, received)
        cpu_percent = tx = rx = 0.0
        if last is not None and now > last[0]:
            elapsed = now - last[0]
            cpu_percent = 100.0 * (cpu - last[1]) / elapsed
            tx, rx = (sent - last[2]) / elapsed, (received - last[3]) / elapsed
        return Sample(self.wall(), round(cpu_percent, 2), round(100.0 * resident / self.total_memory, 3),
                      round(resident / 1e6, 1), round(tx), round(rx))
