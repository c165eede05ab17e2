"""Image View's conversions of sensor_msgs images to browser images."""

import io

import numpy as np
import pytest
from PIL import Image
from rqt_web.images import ImageError, compressed_for_browser, raw_to_png

WIDTH, HEIGHT = 4, 3


def decoded(data: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(data)))


def rgb_pattern() -> np.ndarray:
    pixels = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)
    pixels[..., 0] = np.arange(WIDTH) * 60
    pixels[..., 1] = np.arange(HEIGHT)[:, None] * 100
    pixels[..., 2] = 7
    return pixels


@pytest.mark.parametrize(('encoding', 'channel_order'), [('rgb8', [0, 1, 2]), ('bgr8', [2, 1, 0]),
                                                         ('8UC3', [2, 1, 0])])
def test_colour_images_keep_their_pixels(encoding, channel_order):
    pixels = rgb_pattern()
    data = pixels[..., channel_order].tobytes()
    png = raw_to_png(WIDTH, HEIGHT, encoding, WIDTH * 3, False, data)
    assert png.startswith(b'\x89PNG')
    assert np.array_equal(decoded(png), pixels)


def test_row_padding_is_skipped_and_alpha_kept():
    pixels = np.arange(HEIGHT * WIDTH * 4, dtype=np.uint8).reshape(HEIGHT, WIDTH, 4)
    step = WIDTH * 4 + 5
    data = b''.join(row.tobytes() + b'\x99' * 5 for row in pixels)
    assert np.array_equal(decoded(raw_to_png(WIDTH, HEIGHT, 'rgba8', step, False, data)), pixels)
    bgra = pixels[..., [2, 1, 0, 3]]
    data = b''.join(row.tobytes() + b'\x99' * 5 for row in bgra)[:-5]  # last row without padding
    assert np.array_equal(decoded(raw_to_png(WIDTH, HEIGHT, 'bgra8', step, False, data)), pixels)


def test_mono_images():
    pixels = np.arange(HEIGHT * WIDTH, dtype=np.uint8).reshape(HEIGHT, WIDTH) * 20
    assert np.array_equal(decoded(raw_to_png(WIDTH, HEIGHT, 'mono8', WIDTH, False, pixels.tobytes())), pixels)
    wide = pixels.astype(np.uint16) * 256 + 255
    little = raw_to_png(WIDTH, HEIGHT, 'mono16', WIDTH * 2, False, wide.astype('<u2').tobytes())
    big = raw_to_png(WIDTH, HEIGHT, '16UC1', WIDTH * 2, True, wide.astype('>u2').tobytes())
    assert np.array_equal(decoded(little), pixels)
    assert np.array_equal(decoded(big), pixels)


@pytest.mark.parametrize(('arguments', 'message'), [
    ((WIDTH, HEIGHT, 'yuv422', WIDTH * 2, False, bytes(24)), "unsupported image encoding 'yuv422'"),
    ((WIDTH, HEIGHT, 'rgb8', WIDTH * 3, False, bytes(10)), '10 bytes of data for a 4x3 rgb8 image'),
    ((WIDTH, HEIGHT, 'rgb8', 5, False, bytes(36)), 'step 5 is shorter than a row'),
    ((0, HEIGHT, 'rgb8', 0, False, b''), 'empty image (0x3)'),
])
def test_bad_raw_images_say_why(arguments, message):
    with pytest.raises(ImageError, match=message.replace('(', r'\(').replace(')', r'\)')):
        raw_to_png(*arguments)


def test_compressed_images():
    buffer = io.BytesIO()
    Image.fromarray(rgb_pattern()).save(buffer, format='JPEG')
    jpeg = buffer.getvalue()
    assert compressed_for_browser('jpeg', jpeg) == ('image/jpeg', jpeg)
    png = raw_to_png(WIDTH, HEIGHT, 'rgb8', WIDTH * 3, False, rgb_pattern().tobytes())
    assert compressed_for_browser('rgb8; png compressed bgr8', png) == ('image/png', png)
    buffer = io.BytesIO()
    Image.fromarray(rgb_pattern()).save(buffer, format='BMP')
    content_type, data = compressed_for_browser('bmp', buffer.getvalue())
    assert content_type == 'image/png'
    assert np.array_equal(decoded(data), rgb_pattern())
    with pytest.raises(ImageError, match="cannot decode 5 bytes of compressed image \\(format 'jpeg'\\)"):
        compressed_for_browser('jpeg', b'hello')
