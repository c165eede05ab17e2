"""The pixel bytes of a sensor_msgs/msg/Image as a numpy array and back (rows, step, byte order)."""

from __future__ import annotations

import sys

import numpy as np

from .encodings import Encoding
from .error import CvBridgeError


def byte_array(data: object) -> np.ndarray:
    """A message's uint8[] field (array.array in rclpy, or bytes) as uint8, without a copy."""
    try:
        # object, not a buffer type: a message field can hold anything, and the error says what.
        return np.frombuffer(data, dtype=np.uint8)  # type: ignore[call-overload]
    except (TypeError, ValueError):
        raise CvBridgeError(f'image data must be bytes, not {type(data).__name__}') from None


def image_from_buffer(data: object, height: int, width: int, step: int, encoding: Encoding,
                      is_bigendian: bool) -> np.ndarray:
    """A new native-order array, (height, width) for one channel, (height, width, channels) else."""
    if height <= 0 or width <= 0:
        raise CvBridgeError(f'the image is empty ({width}x{height})')
    row_bytes = width * encoding.channels * encoding.dtype.itemsize
    if step < row_bytes:
        raise CvBridgeError(f'step {step} is shorter than a row of {width} {encoding.name} pixels '
                            f'({row_bytes} bytes)')
    buffer = byte_array(data)
    # The last row may come without its padding, so that much data is enough.
    if buffer.size < step * (height - 1) + row_bytes:
        raise CvBridgeError(f'{buffer.size} bytes of data are too few for a {width}x{height} '
                            f'{encoding.name} image with step {step} (it needs {step * height})')
    rows = np.zeros(step * height, dtype=np.uint8)
    count = min(buffer.size, rows.size)
    rows[:count] = buffer[:count]
    pixels = np.ascontiguousarray(rows.reshape(height, step)[:, :row_bytes])
    stored = encoding.dtype.newbyteorder('>' if is_bigendian else '<')
    image = pixels.view(stored).astype(encoding.dtype, copy=False)
    return image.reshape((height, width) if encoding.channels == 1 else (height, width, encoding.channels))


def is_big_endian(dtype: np.dtype) -> bool:
    """Whether a dtype stores big-endian, native order resolved: the value for is_bigendian."""
    return dtype.byteorder == '>' or (dtype.byteorder == '=' and sys.byteorder == 'big')


def image_to_buffer(image: np.ndarray) -> tuple[bytes, int]:
    """(the rows without padding, step) of an array that check_image accepted."""
    data = image.tobytes()  # row by row (C order) whatever the array's memory layout
    return data, len(data) // image.shape[0]
