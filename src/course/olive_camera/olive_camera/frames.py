"""Whether the camera's images arrive, and how to describe one: display_camera's words, no ROS."""

import numpy as np


class FrameWatch:
    """Follows the arrival times of images, so display_camera says when they start and stop.

    While none arrives, display_camera says which topic it waits for; when they stop, it says so
    once; when they come (back), it says that once.
    """

    def __init__(self, stale_after: float) -> None:
        self.stale_after = stale_after
        self.last: float | None = None  # arrival time of the latest image
        self.receiving = False

    def arrived(self, now: float) -> bool:
        """Note an image; True if it is the first one, or the first after a pause."""
        self.last = now
        first = not self.receiving
        self.receiving = True
        return first

    def check(self, now: float) -> str | None:
        """'waiting' while no image comes, 'stopped' once when they stop; None while they arrive."""
        if self.receiving and self.last is not None and now - self.last > self.stale_after:
            self.receiving = False
            return 'stopped'
        return None if self.receiving else 'waiting'


def describe(image: np.ndarray) -> str:
    """'640x480 colour' / '320x240 grey, 16 bit': what an image from the camera is, in a few words."""
    height, width = image.shape[:2]
    channels = 1 if image.ndim == 2 else image.shape[2]
    kind = {1: 'grey', 3: 'colour', 4: 'colour with alpha'}.get(channels, f'{channels} channels')
    depth = '' if image.dtype == np.uint8 else f', {image.dtype.itemsize * 8} bit'
    return f'{width}x{height} {kind}{depth}'
