"""The camera's renderer: the scene moves the right way with pan and tilt, frames are JPEG."""

import io
import math

import numpy as np
import pytest
from olive_sim.camera_render import LANDMARKS, CameraRenderer, find_colour, focal_length
from PIL import Image

RED = LANDMARKS[0][1]  # the tower straight ahead at pan 0


@pytest.fixture(scope='module')
def renderer():
    return CameraRenderer(640, 480, math.radians(48.66))


def test_the_red_tower_is_centred_at_rest(renderer):
    x, _ = find_colour(renderer.render(0.0, 0.0), RED)
    assert x == pytest.approx(319.5, abs=2)


def test_pan_moves_the_landmark_across_by_the_focal_length(renderer):
    x0, y0 = find_colour(renderer.render(0.0, 0.0), RED)
    x1, y1 = find_colour(renderer.render(0.1, 0.0), RED)
    # Pan turns the camera left (counter-clockwise): the scene moves right by ~f*tan(0.1).
    assert x1 - x0 == pytest.approx(renderer.fx * math.tan(0.1), rel=0.1)
    assert y1 == pytest.approx(y0, abs=2)


def test_tilt_moves_the_landmark_vertically(renderer):
    _, y0 = find_colour(renderer.render(0.0, 0.0), RED)
    x1, y1 = find_colour(renderer.render(0.0, 0.1), RED)
    assert y1 < y0 - 20  # tilting down lifts the scene in the image
    assert x1 == pytest.approx(319.5, abs=3)


def test_looking_behind_shows_the_blue_landmark(renderer):
    image = renderer.render(math.pi, 0.0)
    assert find_colour(image, RED) is None
    assert find_colour(image, LANDMARKS[2][1])[0] == pytest.approx(319.5, abs=3)


def test_jpeg_decodes_to_the_image_size(renderer):
    data = renderer.jpeg(0.2, -0.1, '#1 12:00:00.000', quality=60)
    image = Image.open(io.BytesIO(data))
    assert image.format == 'JPEG' and image.size == (640, 480)
    corner = np.asarray(image.convert('RGB'))[4:20, 6:40]
    assert corner.max() > 200 and corner.min() < 50  # caption: white text on black


def test_focal_length_and_bad_sizes():
    assert focal_length(640, math.radians(90)) == pytest.approx(320)
    with pytest.raises(ValueError, match='too small'):
        CameraRenderer(8, 8, panorama=np.zeros((1800, 3600, 3), np.uint8))
    with pytest.raises(ValueError, match='field of view'):
        CameraRenderer(640, 480, math.radians(179), panorama=np.zeros((1800, 3600, 3), np.uint8))
