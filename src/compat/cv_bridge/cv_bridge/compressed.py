"""JPEG and PNG bytes of a sensor_msgs/msg/CompressedImage to an OpenCV image and back."""

from __future__ import annotations

import cv2
import numpy as np

from .encodings import Encoding, channels_of, cv_type_of, parse_encoding
from .error import CvBridgeError
from .pixels import byte_array

# dst_format -> (file extension for cv2.imencode, the numpy types the format holds).
FORMATS: dict[str, tuple[str, tuple[np.dtype, ...]]] = {
    'jpg': ('.jpg', (np.dtype(np.uint8),)),
    'jpeg': ('.jpg', (np.dtype(np.uint8),)),
    'png': ('.png', (np.dtype(np.uint8), np.dtype(np.uint16))),
}
# What a decoded image is: OpenCV decodes colour to BGR(A).
DECODED = {'8UC1': 'mono8', '16UC1': 'mono16', '8UC3': 'bgr8', '8UC4': 'bgra8'}


def encode(image: np.ndarray, dst_format: object) -> bytes:
    """The compressed bytes of an array that check_image accepted."""
    if not isinstance(dst_format, str) or dst_format.lower() not in FORMATS:
        raise CvBridgeError(f'unsupported compressed format {dst_format!r}; supported: {", ".join(FORMATS)}')
    extension, dtypes = FORMATS[dst_format.lower()]
    if image.dtype not in dtypes:
        # OpenCV would quietly turn it into 8 bits; say so instead.
        holds = ' or '.join(dtype.name for dtype in dtypes)
        raise CvBridgeError(f'{dst_format} holds {holds} images, not {image.dtype}')
    if channels_of(image) == 2:
        raise CvBridgeError(f'{dst_format} holds images of 1, 3 or 4 channels, not 2')
    try:
        ok, buffer = cv2.imencode(extension, image)
    except cv2.error as error:
        raise CvBridgeError(f'OpenCV cannot encode this image as {dst_format}: {one_line(error)}') from None
    if not ok:
        raise CvBridgeError(f'OpenCV cannot encode this image as {dst_format}')
    return buffer.tobytes()


def decode(data: object, image_format: str) -> np.ndarray:
    """The image in compressed bytes, with its channels and depth as stored (IMREAD_UNCHANGED)."""
    buffer = byte_array(data)
    if buffer.size == 0:
        raise CvBridgeError('the compressed image has no data')
    try:
        image = cv2.imdecode(buffer, cv2.IMREAD_UNCHANGED)
    except cv2.error as error:
        raise CvBridgeError(f'cannot decode the compressed image: {one_line(error)}') from None
    if image is None:
        raise CvBridgeError(f'cannot decode {buffer.size} bytes of compressed image (format '
                            f'{image_format!r}): not an image OpenCV reads')
    return image


def decoded_encoding(image: np.ndarray) -> Encoding:
    """The encoding a decoded image is in: mono8, mono16, bgr8, bgra8, or its plain OpenCV type."""
    cv_type = cv_type_of(image)
    return parse_encoding(DECODED.get(cv_type, cv_type))


def one_line(error: Exception) -> str:
    """OpenCV's message without its trailing newline (cv2.error messages are one line)."""
    lines = [line.strip() for line in str(error).splitlines() if line.strip()]
    return lines[0] if lines else type(error).__name__
