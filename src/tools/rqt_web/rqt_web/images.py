"""Image View: sensor_msgs images as bytes a browser shows (node-free)."""

import io

import numpy as np
from PIL import Image

# encoding -> (channels, bytes per channel, channel order for Pillow); 8UC3 is BGR, as cv_bridge reads it.
RAW_ENCODINGS = {
    'rgb8': (3, 1, 'RGB'), 'bgr8': (3, 1, 'BGR'), 'rgba8': (4, 1, 'RGBA'), 'bgra8': (4, 1, 'BGRA'),
    'mono8': (1, 1, 'L'), '8UC1': (1, 1, 'L'), '8UC3': (3, 1, 'BGR'), '8UC4': (4, 1, 'BGRA'),
    'mono16': (1, 2, 'L'), '16UC1': (1, 2, 'L'),
}
JPEG_MAGIC = b'\xff\xd8\xff'
PNG_MAGIC = b'\x89PNG\r\n\x1a\n'


class ImageError(ValueError):
    """An image that cannot be shown; str() says why in one line."""


def raw_to_png(width: int, height: int, encoding: str, step: int, is_bigendian: bool,
               data: bytes) -> bytes:
    """A sensor_msgs/msg/Image's pixels as PNG (16-bit mono scaled to 8 bits)."""
    if encoding not in RAW_ENCODINGS:
        raise ImageError(f"unsupported image encoding '{encoding}' "
                         f"(supported: {', '.join(RAW_ENCODINGS)})")
    channels, depth, order = RAW_ENCODINGS[encoding]
    row_bytes = width * channels * depth
    if width <= 0 or height <= 0:
        raise ImageError(f'empty image ({width}x{height})')
    if step < row_bytes:
        raise ImageError(f'step {step} is shorter than a row of {width} {encoding} pixels '
                         f'({row_bytes} bytes)')
    if len(data) < step * (height - 1) + row_bytes:
        raise ImageError(f'{len(data)} bytes of data for a {width}x{height} {encoding} image '
                         f'with step {step} (need {step * height})')
    # The last row may come without its padding.
    padded = bytes(data[:step * height]).ljust(step * height, b'\0')
    pixels = np.frombuffer(padded, dtype=np.uint8).reshape(height, step)[:, :row_bytes]
    if depth == 2:
        pixels = np.ascontiguousarray(pixels).view('>u2' if is_bigendian else '<u2')
        pixels = (pixels >> 8).astype(np.uint8)
    pixels = np.ascontiguousarray(pixels).reshape(height, width, channels)
    if order == 'BGR':
        pixels = pixels[:, :, ::-1]
    elif order == 'BGRA':
        pixels = pixels[:, :, [2, 1, 0, 3]]
    image = Image.fromarray(np.ascontiguousarray(pixels[:, :, 0] if channels == 1 else pixels))
    return encode_png(image)


def encode_png(image: Image.Image) -> bytes:
    """The image as PNG bytes, compressed lightly (it only goes to localhost)."""
    buffer = io.BytesIO()
    image.save(buffer, format='PNG', compress_level=1)  # speed over size: it goes to localhost
    return buffer.getvalue()


def compressed_for_browser(image_format: str, data: bytes) -> tuple[str, bytes]:
    """(content type, bytes) of a sensor_msgs/msg/CompressedImage, for a browser to show.

    JPEG and PNG go as they are, anything else Pillow reads as PNG; ImageError for bytes it cannot
    decode.
    """
    if data.startswith(JPEG_MAGIC):
        return 'image/jpeg', data
    if data.startswith(PNG_MAGIC):
        return 'image/png', data
    try:
        image = Image.open(io.BytesIO(data))
        image.load()
    except Exception as error:  # Pillow raises many kinds for undecodable bytes
        raise ImageError(f"cannot decode {len(data)} bytes of compressed image (format "
                         f"'{image_format}'): {str(error).splitlines()[0] if str(error) else error!r}"
                         ) from None
    return 'image/png', encode_png(image.convert('RGBA' if 'A' in image.mode else 'RGB'))
