"""find_colour: where a colour is in an RGB picture."""

import numpy as np
import pytest
from owl_common.images import find_colour

RED = (215, 20, 28)


def picture() -> np.ndarray:
    """A grey 40x30 picture with a red 6x4 block whose pixels' centre is at x 12.5, y 20.5."""
    rgb = np.full((30, 40, 3), 128, dtype=np.uint8)
    rgb[19:23, 10:16] = RED
    return rgb


def test_the_centre_of_the_colours_pixels_is_found():
    assert find_colour(picture(), RED) == pytest.approx((12.5, 20.5))


def test_a_close_colour_counts_and_a_far_one_does_not():
    assert find_colour(picture(), (235, 40, 48)) == pytest.approx((12.5, 20.5))  # within 60 in each channel
    assert find_colour(picture(), (0, 0, 255)) is None
    assert find_colour(picture(), (235, 40, 48), tolerance=10) is None


def test_fewer_than_20_pixels_are_not_a_find():
    rgb = np.full((30, 40, 3), 128, dtype=np.uint8)
    rgb[0:4, 0:4] = RED  # 16 pixels: noise, not an object
    assert find_colour(rgb, RED) is None
    rgb[4, 0:4] = RED
    assert find_colour(rgb, RED) == pytest.approx((1.5, 2.0))
