"""SignalProcess: send a signal to some processes."""

from __future__ import annotations

from launch.events.process.process_targeted_event import ProcessMatcher, ProcessTargetedEvent


class SignalProcess(ProcessTargetedEvent):
    """Send a signal to the matching processes."""

    def __init__(self, *, signal_number: int, process_matcher: ProcessMatcher) -> None:
        super().__init__(process_matcher=process_matcher)
        self.signal = signal_number
