"""display_camera's words about arriving images: waiting, receiving, stopped; an image described."""

import numpy as np
import pytest
from olive_camera.frames import FrameWatch, describe


def test_waiting_until_the_first_image_then_quiet_while_images_arrive():
    watch = FrameWatch(stale_after=2.0)
    assert watch.check(0.0) == 'waiting'
    assert watch.check(10.0) == 'waiting'
    assert watch.arrived(10.5) is True     # the first image: said once
    assert watch.arrived(10.6) is False
    assert watch.check(11.0) is None
    assert watch.check(12.6) is None       # 2.0 s since the last image: not yet stale


def test_images_that_stop_are_said_once_then_waited_for_again():
    watch = FrameWatch(stale_after=2.0)
    watch.arrived(1.0)
    assert watch.check(3.1) == 'stopped'
    assert watch.check(4.0) == 'waiting'
    assert watch.check(9.0) == 'waiting'
    assert watch.arrived(9.5) is True      # back: said again
    assert watch.check(10.0) is None


@pytest.mark.parametrize(('image', 'words'), [
    (np.zeros((480, 640, 3), np.uint8), '640x480 colour'),
    (np.zeros((240, 320), np.uint8), '320x240 grey'),
    (np.zeros((240, 320), np.uint16), '320x240 grey, 16 bit'),
    (np.zeros((2, 4, 4), np.uint8), '4x2 colour with alpha'),
    (np.zeros((2, 4, 2), np.uint8), '4x2 2 channels'),
])
def test_describe(image, words):
    assert describe(image) == words
