"""The robot view's live plots as plain data (node-free), decimated into buckets.

Samples of the servos' goal, position and effort and of the IMU's roll, pitch and yaw, decimated
into buckets and kept for a rolling window, and the columns a page is sent.

Why buckets: the joints and the IMU come at 100 Hz each; a plot 10 s wide and a few hundred pixels
across shows no more than 50 points a second, and the page's WebSocket should carry only what it
shows. A bucket holds the mean of each series' samples that fell into it; a *held* series (a goal,
which is a step, not a stream) keeps its last value in every bucket after it, so the plot draws
the step where it happened.

Why overlap: each push repeats the last OVERLAP seconds already pushed, and the page replaces
what it has from the batch's first time on (plot_data.js, mergeBatch): the bucket still filling
when a batch was made is sent again complete. And owl_web replaces an update not yet sent to a slow
page by a newer one (pages want state, not a backlog): a batch made while the last one still waits
begins where that one did, so no number of replaced batches leaves a gap in the plot (a page held
up that way most likely lost the middle of a servo's step in a suite run: its rise read 0.34 s for 0.26).

Why sample times: the node times each sample by when it was measured (its message's stamp), not
by when the node got round to it. On a busy machine a node handles several messages of a topic
at once after a delay, and timed on arrival a servo's 0.36 s rise to a goal was plotted as 0.2 s.
A sample up to LATE behind the newest bucket therefore goes in its own bucket (still within what
the next push repeats); a stamp from a clock far from the node's is not trusted (sample_time).
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field

BUCKET = 0.02   # s: 50 points a second in the plot
WINDOW = 60.0   # s kept and sent at once to a new page: the widest window a page may show
OVERLAP = 0.5   # s each push repeats of the previous one
LATE = OVERLAP / 2  # s behind the newest bucket a sample may be and still go in its own bucket
STAMP_TRUSTED = 1.0  # s: an older stamp, or one from the future, says the clocks differ
DECIMALS = 4    # of a value sent (0.1 mrad, 0.1 mN*m: finer than any plot shows)


def sample_time(stamp_ns: int | None, now: float) -> float:
    """The time (s) to plot a sample at: its stamp (ns since the epoch), or `now` (time.time()).

    `now` is taken when the sample has no stamp or when the stamp is more than STAMP_TRUSTED away
    from now (another machine's clock, a module that was never set).
    """
    if stamp_ns is None:
        return now
    stamp = stamp_ns / 1e9
    return stamp if now - STAMP_TRUSTED <= stamp <= now + 0.01 else now


@dataclass
class Bucket:
    """One time slice of a PlotWindow: the sums and counts of its samples, and the held series' values."""

    index: int  # start time / BUCKET
    sums: dict[str, float] = field(default_factory=dict)
    counts: dict[str, int] = field(default_factory=dict)
    held: dict[str, float] = field(default_factory=dict)
    held_here: set[str] = field(default_factory=set)  # held series whose value changed in this bucket

    def value(self, series: str) -> float | None:
        """The series' value in this bucket: the held value, else the mean of its samples; None for none."""
        if series in self.held:
            return self.held[series]
        count = self.counts.get(series, 0)
        return self.sums[series] / count if count else None


class PlotWindow:
    """Samples of named series in time order, decimated into buckets of `bucket` seconds.

    They are kept for `window` (+ OVERLAP) seconds. Times are any clock's seconds (the node uses
    time.time(), the clock of the messages' stamps, see sample_time).
    """

    def __init__(self, series: Iterable[str], held: Iterable[str] = (), bucket: float = BUCKET,
                 window: float = WINDOW) -> None:
        self.series = tuple(series)
        self.held_series = frozenset(held)
        unknown = self.held_series - set(self.series)
        if unknown:
            raise ValueError(f'held series not among the series: {", ".join(sorted(unknown))}')
        if not bucket > 0 or not window > bucket:
            raise ValueError(f'need 0 < bucket < window, got bucket {bucket}, window {window}')
        self.bucket = bucket
        self.window = window
        self._buckets: deque[Bucket] = deque()

    def add(self, time: float, values: dict[str, float]) -> None:
        """Add samples taken at `time` (seconds), one value per series.

        Samples may come a little out of order (each topic's own messages are in order, different
        topics' are not): one up to LATE behind the newest bucket goes in its own bucket, an older
        one in the newest. Non-finite values and unknown series are refused with ValueError (the
        node checks what it takes from ROS).
        """
        for name, value in values.items():
            if name not in self.series:
                raise ValueError(f"unknown series '{name}'; known: {', '.join(self.series)}")
            if not math.isfinite(value):
                raise ValueError(f'{name}: {value} is not a finite number')
        # the small nudge keeps a time on a bucket's edge (5.00 s / 0.02 s) in the bucket it starts
        position = self._bucket_at(math.floor(time / self.bucket + 1e-6))
        bucket = self._buckets[position]
        for name, value in values.items():
            if name in self.held_series:
                self._hold(position, name, value)
            else:
                bucket.sums[name] = bucket.sums.get(name, 0.0) + value
                bucket.counts[name] = bucket.counts.get(name, 0) + 1
        self._trim()

    def _bucket_at(self, index: int) -> int:
        """The position in self._buckets of the bucket a sample of bucket index `index` goes in."""
        buckets = self._buckets
        if not buckets or index > buckets[-1].index:  # a new bucket holds what the newest held
            buckets.append(Bucket(index, held=dict(buckets[-1].held) if buckets else {}))
            return len(buckets) - 1
        if index < buckets[-1].index - round(LATE / self.bucket):
            return len(buckets) - 1
        position = len(buckets) - 1
        while position > 0 and buckets[position - 1].index >= index:
            position -= 1
        if buckets[position].index != index:  # no sample in that bucket yet: begin it in between
            before = buckets[position - 1].held if position > 0 else {}
            buckets.insert(position, Bucket(index, held=dict(before)))
        return position

    def _hold(self, position: int, name: str, value: float) -> None:
        """Set a held series to value in the bucket at `position` and in every later one.

        The later ones stop at the next bucket where the series changed again.
        """
        buckets = self._buckets
        buckets[position].held_here.add(name)
        for later in range(position, len(buckets)):
            if later > position and name in buckets[later].held_here:
                return
            buckets[later].held[name] = value

    def _trim(self) -> None:
        oldest = self._buckets[-1].index - math.ceil((self.window + OVERLAP) / self.bucket)
        while self._buckets and self._buckets[0].index < oldest:
            self._buckets.popleft()

    def newest(self) -> float | None:
        """The start time of the newest bucket, or None before the first sample."""
        return self._buckets[-1].index * self.bucket if self._buckets else None

    def columns(self, since: float = -math.inf) -> dict[str, list[float | None]]:
        """The columns of the buckets that start at or after `since`, oldest first: a page's plot data.

        {'t': bucket start times, <series>: values (None where a bucket has no sample)}, the shape
        uPlot takes.
        """
        chosen = [b for b in self._buckets if b.index * self.bucket >= since - 1e-9]
        columns: dict[str, list[float | None]] = {'t': [round(b.index * self.bucket, 3) for b in chosen]}
        for name in self.series:
            values = (b.value(name) for b in chosen)
            columns[name] = [None if v is None else round(v, DECIMALS) for v in values]
        return columns


class PushCursor:
    """Where one page's pushes are, so each push sends what is new and a little overlap.

    The first push sends the whole window, each later one what is new plus OVERLAP seconds of what
    was sent (see the module's docstring).
    """

    def __init__(self) -> None:
        self.since = -math.inf  # the first batch: everything the window has
        self.sent_newest: float | None = None
        self._last_start = -math.inf  # where the last batch began

    def batch(self, window: PlotWindow, last_sent: bool = True) -> dict[str, list[float | None]] | None:
        """The next batch for this page, or None when no bucket was begun since the last one.

        last_sent False (the last batch still waits to be sent, and this one will take its place):
        it begins where the last one began.
        """
        newest = window.newest()
        if newest is None or newest == self.sent_newest:
            return None
        start = self.since if last_sent else self._last_start
        columns = window.columns(start)
        self._last_start = start
        self.since = newest - OVERLAP
        self.sent_newest = newest
        return columns
