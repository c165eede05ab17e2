"""Where a servo was when a picture was taken: its recent joint states, looked up by their stamps.

A tracker that adds the ball's offset in a picture to where the head is *now* turns too far when
the picture is late (a busy machine, a slow network): the head has moved since the picture was
taken. Added to where the head was *then*, the offset points at the ball whatever the delay.
"""

from __future__ import annotations

from collections import deque

KEEP_NS = 2_000_000_000  # ns of joint states kept: a picture later than that is too late to steer by


class JointHistory:
    """A servo's positions of the last KEEP_NS, each with its joint state's stamp (ns)."""

    def __init__(self) -> None:
        self._samples: deque[tuple[int, float]] = deque()

    def add(self, stamp_ns: int, position: float) -> None:
        """Keep a joint state; one stamped before the newest kept (another clock, a restart) starts anew."""
        if self._samples and stamp_ns < self._samples[-1][0]:
            self._samples.clear()
        self._samples.append((stamp_ns, position))
        while self._samples[0][0] < stamp_ns - KEEP_NS:
            self._samples.popleft()

    def latest(self) -> float | None:
        return self._samples[-1][1] if self._samples else None

    def at(self, stamp_ns: int) -> float | None:
        """The position at stamp_ns, between the two joint states around it.

        The latest one for a stamp after them all, or before them all: a picture stamped by a clock
        other than the servo's (or not at all) is steered by as it always was, from where the head is.
        """
        if not self._samples:
            return None
        if not self._samples[0][0] <= stamp_ns <= self._samples[-1][0]:
            return self._samples[-1][1]
        before = self._samples[0]
        for after in self._samples:
            if after[0] >= stamp_ns:
                if after[0] == before[0]:
                    return after[1]
                share = (stamp_ns - before[0]) / (after[0] - before[0])
                return before[1] + share * (after[1] - before[1])
            before = after
        return self._samples[-1][1]
