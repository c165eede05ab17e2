"""Finding the red ball and the goals that centre it, on synthetic images."""

import math

import cv2
import numpy as np
import pytest
from olive_vision.red_ball import angle_offsets, find_red_ball, tracking_goals

WIDTH, HEIGHT = 640, 480
FOV = math.radians(48.66)


def scene(*discs):
    """A grey-green BGR image with filled discs of (x, y, radius, BGR colour)."""
    image = np.full((HEIGHT, WIDTH, 3), (80, 110, 90), dtype=np.uint8)
    for x, y, radius, colour in discs:
        cv2.circle(image, (x, y), radius, colour, -1)
    return image


def test_the_biggest_red_blob_is_the_ball():
    image = scene((100, 100, 8, (30, 20, 215)), (400, 300, 25, (28, 20, 215)))
    x, y, area = find_red_ball(image, 40)
    assert (x, y) == pytest.approx((400, 300), abs=0.5)
    assert area == pytest.approx(math.pi * 25 ** 2, rel=0.05)


@pytest.mark.parametrize('colour', [(20, 140, 240), (150, 185, 225), (200, 40, 200), (245, 245, 245),
                                    (40, 70, 120)], ids=['orange', 'skin', 'magenta', 'white', 'brown'])
def test_colours_near_red_are_not_the_ball(colour):
    assert find_red_ball(scene((320, 240, 30, colour)), 40) is None


def test_a_speck_smaller_than_min_area_is_not_the_ball():
    assert find_red_ball(scene((320, 240, 2, (30, 20, 215))), 40) is None
    assert find_red_ball(scene(), 40) is None


def test_offsets_are_the_angles_from_the_middle():
    assert angle_offsets((WIDTH - 1) / 2, (HEIGHT - 1) / 2, WIDTH, HEIGHT, FOV) == pytest.approx((0.0, 0.0))
    right, down = angle_offsets(WIDTH - 0.5, 0.0, WIDTH, HEIGHT, FOV)
    assert right == pytest.approx(FOV / 2, abs=0.002)  # the right edge: half the field of view
    assert down < 0  # the top row is up


def test_a_ball_right_and_below_turns_the_head_right_and_down():
    pan, tilt = tracking_goals(0.2, -0.1, 0.05, 0.03, 1.0, 1.0)
    assert (pan, tilt) == pytest.approx((0.15, -0.07))  # positive pan turns left, positive tilt looks down
    assert tracking_goals(0.2, -0.1, 0.05, 0.03, 0.5, 0.0) == pytest.approx((0.175, -0.1))
