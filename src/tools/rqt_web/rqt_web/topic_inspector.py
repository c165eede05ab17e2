"""What the topic inspector shows of a topic, as plain data (node-free).

Its rate measured from the messages' arrivals, its last message cut to what a page can show, and
its publishers and subscribers with their QoS. The rqt node subscribes and pushes (channel "topic").
"""

from __future__ import annotations

from collections import deque
from typing import Any

from owl_common.graph import full_node_name
from owl_web.codec import json_safe

RATE_WINDOW = 5.0  # s of arrivals a rate is measured over
SHOWN_ITEMS = 16  # items of a sequence shown; the rest are counted (an image's data is 921,600 bytes)
SHOWN_CHARACTERS = 200  # of a string


class ArrivalRate:
    """Messages a second over the last RATE_WINDOW s, from their arrival times (s, one clock)."""

    def __init__(self, window: float = RATE_WINDOW) -> None:
        self._window = window
        self._times: deque[float] = deque()

    def add(self, now: float) -> None:
        """A message arrived at now."""
        self._times.append(now)
        self._forget(now)

    def rate(self, now: float) -> float | None:
        """The rate; None with fewer than two messages in the window, or none for a second and two periods."""
        self._forget(now)
        if len(self._times) < 2 or self._times[-1] <= self._times[0]:
            return None
        period = (self._times[-1] - self._times[0]) / (len(self._times) - 1)
        return None if now - self._times[-1] > 1.0 + 2 * period else 1 / period

    def _forget(self, now: float) -> None:
        while self._times and self._times[0] < now - self._window:
            self._times.popleft()


def message_summary(value: Any, shown_items: int = SHOWN_ITEMS) -> Any:
    """A message (or a field of one) as JSON-safe data, long sequences and strings cut.

    A sequence keeps its first shown_items items and then says how many more there are; the cut
    comes before any conversion, so an image costs as little as a pose.
    """
    if hasattr(value, 'get_fields_and_field_types'):
        return {name: message_summary(getattr(value, name), shown_items)
                for name in value.get_fields_and_field_types()}
    if isinstance(value, str):
        extra = len(value) - SHOWN_CHARACTERS
        return value if extra <= 0 else f'{value[:SHOWN_CHARACTERS]}... ({extra} more characters)'
    if isinstance(value, (bytes, bytearray)) or (hasattr(value, '__len__') and hasattr(value, '__getitem__')
                                                 and not isinstance(value, dict)):
        shown = [message_summary(item, shown_items) for item in value[:shown_items]]
        extra = len(value) - shown_items
        return [*shown, f'... ({extra} more)'] if extra > 0 else shown
    if hasattr(value, 'item'):  # a numpy scalar of a fixed-size array's
        value = value.item()
    return json_safe(value)


def endpoint_summary(endpoint: dict[str, Any]) -> dict[str, Any]:
    """A publisher or subscriber (owl_common.graph.endpoint_to_dict's) as the inspector lists it.

    The policies discovery tells of another node's endpoint: its history and depth it does not (as
    `ros2 topic info -v` says, UNKNOWN), so they are left out.
    """
    return {'node': full_node_name(endpoint['node_namespace'], endpoint['node_name']),
            'reliability': endpoint['reliability'],
            'durability': endpoint['durability'], 'liveliness': endpoint['liveliness']}
