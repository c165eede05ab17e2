"""The camera's renderer: the scene moves the right way with pan and tilt, frames are JPEG."""

import io
import math
import os
import time

import numpy as np
import pytest
from olive_sim.camera_render import (
    LANDMARKS,
    NO_RED_LANDMARKS,
    PANORAMA_HEIGHT,
    PANORAMA_WIDTH,
    UNUSED_PANORAMA_KEPT,
    CameraRenderer,
    CaptionWriter,
    SplicedJpeg,
    _font,
    build_panorama,
    encode_jpeg,
    focal_length,
    join_jpeg,
    packed_panorama,
    scene_pixels,
    split_jpeg,
)
from owl_common.images import find_colour
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
    assert image.format == 'JPEG'
    assert image.size == (640, 480)
    corner = np.asarray(image.convert('RGB'))[4:20, 6:40]
    assert corner.max() > 200
    assert corner.min() < 50  # caption: white text on black


def test_focal_length_and_bad_sizes():
    assert focal_length(640, math.radians(90)) == pytest.approx(320)
    with pytest.raises(ValueError, match='too small'):
        CameraRenderer(8, 8, panorama=np.zeros((1800, 3600, 3), np.uint8))
    with pytest.raises(ValueError, match='field of view'):
        CameraRenderer(640, 480, math.radians(179), panorama=np.zeros((1800, 3600, 3), np.uint8))


def coordinate_panorama() -> np.ndarray:
    """A panorama whose pixels encode their own (row, column): row * width + column as 24-bit RGB."""
    rows, columns = np.mgrid[0:PANORAMA_HEIGHT, 0:PANORAMA_WIDTH]
    code = (rows * PANORAMA_WIDTH + columns).astype(np.uint32)
    return np.stack([code >> 16, (code >> 8) & 255, code & 255], axis=-1).astype(np.uint8)


def direct_lookup(width, height, fov, pan, tilt):
    """Panorama (row, column) of every pixel, straight from each pixel's ray (no mirroring)."""
    f = focal_length(width, fov)
    u = (np.arange(width, dtype=np.float32) - (width - 1) / 2) / f
    v = (np.arange(height, dtype=np.float32) - (height - 1) / 2) / f
    right, down = np.meshgrid(u, v)
    left, up = -right, -down
    c, s = np.float32(math.cos(tilt)), np.float32(math.sin(tilt))
    azimuth = np.arctan2(left, c + s * up)
    inverse_length = 1.0 / np.sqrt(1.0 + right * right + down * down)
    elevation = np.arcsin(np.clip((c * up - s) * inverse_length, -1, 1))
    columns = np.rint(azimuth * np.float32(PANORAMA_WIDTH / (2 * math.pi))).astype(np.int64)
    columns = (columns + round(pan * PANORAMA_WIDTH / (2 * math.pi))) % PANORAMA_WIDTH
    rows = np.rint((np.float32(math.pi / 2) - elevation) * np.float32(PANORAMA_HEIGHT / math.pi))
    return np.clip(rows, 0, PANORAMA_HEIGHT - 1).astype(np.int64), columns


@pytest.mark.parametrize(('width', 'height', 'fov_deg'),
                         [(640, 480, 48.66), (17, 23, 90.0), (100, 60, 150.0)])
def test_every_pixel_samples_the_panorama_where_its_ray_points(width, height, fov_deg):
    # The renderer computes one half of the view and mirrors it: the result must be exact.
    fov = math.radians(fov_deg)
    renderer = CameraRenderer(width, height, fov, panorama=coordinate_panorama())
    for pan, tilt in ((0.0, 0.0), (0.7, 0.3), (-2.5, -1.2), (3.5, 1.5)):
        rgb = renderer.render(pan, tilt).astype(np.int64)
        code = (rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]
        rows, columns = direct_lookup(width, height, fov, pan, tilt)
        assert np.array_equal(code // PANORAMA_WIDTH, rows)
        assert np.array_equal(code % PANORAMA_WIDTH, columns)


def test_caption_is_white_on_a_black_box_and_leaves_the_rest():
    writer = CaptionWriter(_font(16))
    frame = np.full((40, 120), 0x00808080, dtype=np.uint32)
    writer.draw(frame, '#12', 6, 4)
    rgb = frame.view(np.uint8).reshape(40, 120, 4)[..., :3]
    box = rgb[2:4 + writer.line_height + 2, 3:40]
    assert box.max() > 200
    assert box.min() == 0
    assert (rgb[..., 0] == rgb[..., 1]).all()
    assert (rgb[..., 1] == rgb[..., 2]).all()  # grey only
    assert (rgb[:, 60:] == 128).all()
    assert (rgb[4 + writer.line_height + 2:] == 128).all()


def test_a_caption_wider_than_the_frame_is_cut_off():
    writer = CaptionWriter(_font(16))
    frame = np.zeros((16, 16), dtype=np.uint32)
    writer.draw(frame, '#123456789  12:00:00.000', 6, 4)
    assert frame.view(np.uint8).max() > 200


def test_small_frames_encode_with_their_caption():
    data = CameraRenderer(16, 16, panorama=coordinate_panorama()).jpeg(0.0, 0.0, '#1 12:00:00.000')
    assert Image.open(io.BytesIO(data)).size == (16, 16)


@pytest.fixture(scope='module')
def coordinates_renderer():
    return CameraRenderer(100, 60, math.radians(60), panorama=coordinate_panorama())


def test_split_and_join_give_back_the_jpeg():
    frame = np.arange(64 * 48, dtype=np.uint32).reshape(48, 64) * 2654435761
    data = encode_jpeg(frame, 80)
    head, rows = split_jpeg(data)
    assert len(rows) == 3  # 48 px of 16-px block rows
    assert join_jpeg(head, rows) == data


def test_a_frame_with_the_same_view_is_the_full_encoding_byte_for_byte(coordinates_renderer):
    fresh = CameraRenderer(100, 60, math.radians(60), panorama=coordinate_panorama())
    coordinates_renderer.jpeg(0.4, 0.2, '#1  12:00:00.000')
    again = coordinates_renderer.jpeg(0.4, 0.2, '#2  12:00:00.033')  # only the caption is encoded
    assert again == fresh.jpeg(0.4, 0.2, '#2  12:00:00.033')
    # A new view, or a new quality, is encoded whole.
    assert coordinates_renderer.jpeg(0.5, 0.2, '#3') == fresh.jpeg(0.5, 0.2, '#3')
    assert coordinates_renderer.jpeg(0.5, 0.2, '#4', 30) == fresh.jpeg(0.5, 0.2, '#4', 30)


def test_spliced_jpeg_replaces_only_the_top_rows():
    encoder = SplicedJpeg(height=64, top=20)
    assert encoder.top == 32
    frame = np.zeros((64, 32), dtype=np.uint32)
    rgb = frame.view(np.uint8).reshape(64, 32, 4)[..., :3]
    rgb[:] = (30, 60, 90)
    encoder.encode(frame, 80, rest_unchanged=False)
    rgb[:32] = (220, 200, 10)
    assert encoder.encode(frame, 80, rest_unchanged=True) == encode_jpeg(frame, 80)
    decoded = np.asarray(Image.open(io.BytesIO(encode_jpeg(frame, 80))))
    assert decoded[5, 5, 0] > 200
    assert decoded[60, 5, 0] < 50


def test_the_scene_is_built_once_into_a_shared_file_and_a_broken_file_is_built_again(tmp_path):
    built = scene_pixels(NO_RED_LANDMARKS, tmp_path)
    [saved] = tmp_path.glob('panorama-*.npy')
    assert np.array_equal(built, packed_panorama(build_panorama(NO_RED_LANDMARKS)))
    mapped = scene_pixels(NO_RED_LANDMARKS, tmp_path)
    assert isinstance(mapped, np.memmap)
    assert not mapped.flags.writeable
    assert np.array_equal(mapped, built)
    assert len(list(tmp_path.glob('panorama-*.npy'))) == 1
    scene_pixels(LANDMARKS, tmp_path)  # other landmarks, another file
    assert len(list(tmp_path.glob('panorama-*.npy'))) == 2
    saved.write_bytes(saved.read_bytes()[:1000])  # cut short, as by a full disk
    assert np.array_equal(scene_pixels(NO_RED_LANDMARKS, tmp_path), built)
    assert np.array_equal(np.load(saved), built)


def test_a_cached_scene_unused_for_a_week_goes_when_another_is_written(tmp_path):
    unused, used = tmp_path / 'panorama-0000000000000000.npy', tmp_path / 'panorama-1111111111111111.npy'
    unused.write_bytes(b'an old version')
    used.write_bytes(b'a version in use elsewhere')
    week_ago = time.time() - UNUSED_PANORAMA_KEPT - 60
    os.utime(unused, (week_ago, week_ago))
    scene_pixels(LANDMARKS, tmp_path)
    assert not unused.exists()
    assert used.exists()
    assert len(list(tmp_path.glob('panorama-*.npy'))) == 2


def test_without_a_writable_cache_the_scene_is_built_in_memory(tmp_path):
    blocked = tmp_path / 'not_a_folder'
    blocked.write_text('')
    pixels = scene_pixels(LANDMARKS, blocked)
    assert pixels.shape == (PANORAMA_HEIGHT * 2 * PANORAMA_WIDTH,)
    assert not isinstance(pixels, np.memmap)
