"""Looking for things in camera pictures (numpy RGB arrays): the simulator's tests, the demo, the tests."""

from __future__ import annotations

import numpy as np


def find_colour(rgb: np.ndarray, colour: tuple[int, int, int],
                tolerance: int = 60) -> tuple[float, float] | None:
    """Centroid (x, y) in pixels of the pixels within `tolerance` of `colour`, or None."""
    distance = np.abs(rgb.astype(np.int16) - np.array(colour, dtype=np.int16)).max(axis=2)
    ys, xs = np.nonzero(distance < tolerance)
    if len(xs) < 20:
        return None
    return float(xs.mean()), float(ys.mean())
