"""Image encodings as numpy sees them, and conversion between the named colour ones.

An encoding is either a named one of sensor_msgs' image_encodings (mono8, bgr8, ...), which fixes
the colour order, or a plain OpenCV type such as 8UC3 or 32FC1 (depth, 'C', channel count), which
is what 'passthrough' gives an array with no colour meaning.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import cv2
import numpy as np

from .error import CvBridgeError

PASSTHROUGH = 'passthrough'

# OpenCV depth names by numpy (kind, item size).
DEPTHS: dict[tuple[str, int], str] = {
    ('u', 1): '8U', ('i', 1): '8S', ('u', 2): '16U', ('i', 2): '16S',
    ('i', 4): '32S', ('f', 4): '32F', ('f', 8): '64F',
}
DTYPES: dict[str, np.dtype] = {depth: np.dtype(f'{kind}{size}') for (kind, size), depth in DEPTHS.items()}
CV_TYPE = re.compile(r'(8U|8S|16U|16S|32S|32F|64F)C([1-4])')

# Named encoding -> (colour order as OpenCV's COLOR_* constants spell it, OpenCV type).
NAMED: dict[str, tuple[str, str]] = {
    'mono8': ('GRAY', '8UC1'), 'mono16': ('GRAY', '16UC1'),
    'bgr8': ('BGR', '8UC3'), 'rgb8': ('RGB', '8UC3'),
    'bgra8': ('BGRA', '8UC4'), 'rgba8': ('RGBA', '8UC4'),
}
SUPPORTED = f'{", ".join(NAMED)}, {PASSTHROUGH} or an OpenCV type such as 8UC3 or 32FC1'


@dataclass(frozen=True)
class Encoding:
    """A parsed encoding: its name, numpy dtype, channel count and, for a named one, colour order."""

    name: str
    dtype: np.dtype  # native byte order
    channels: int
    order: str | None  # colour order of a named encoding; None for a plain OpenCV type

    @property
    def cv_type(self) -> str:
        """The OpenCV type with this dtype and channel count, e.g. 8UC3 for bgr8."""
        return f'{DEPTHS[(self.dtype.kind, self.dtype.itemsize)]}C{self.channels}'


def parse_encoding(name: object) -> Encoding:
    """The Encoding an encoding string names ('passthrough' is not one: callers resolve it)."""
    if not isinstance(name, str):
        raise CvBridgeError(f'an encoding is a string such as bgr8, not {type(name).__name__}')
    order, cv_type = NAMED.get(name, (None, name))
    match = CV_TYPE.fullmatch(cv_type)
    if match is None:
        shown = repr(name) if name else "'' (an empty encoding: was the message filled in?)"
        raise CvBridgeError(f'unsupported encoding {shown}; supported: {SUPPORTED}')
    return Encoding(name, DTYPES[match[1]], int(match[2]), order)


def depth_of(dtype: np.dtype) -> str:
    """OpenCV's depth name for a dtype (8U, 32F, ...); CvBridgeError if OpenCV has none for it."""
    depth = DEPTHS.get((dtype.kind, dtype.itemsize))
    if depth is None:
        raise CvBridgeError(f'an image array of {dtype} has no OpenCV type; use uint8, int8, uint16, '
                            'int16, int32, float32 or float64')
    return depth


def check_image(image: object) -> np.ndarray:
    """The array itself if it can be an OpenCV image, else a CvBridgeError saying why not."""
    if not isinstance(image, np.ndarray):
        raise CvBridgeError(f'expected an OpenCV image (a numpy array), not {type(image).__name__}')
    if image.ndim not in (2, 3):
        raise CvBridgeError(f'an image array has the shape (height, width) or (height, width, channels), '
                            f'not {image.shape}')
    if image.ndim == 3 and not 1 <= image.shape[2] <= 4:
        raise CvBridgeError(f'an image has 1 to 4 channels, not {image.shape[2]} (shape {image.shape})')
    if image.size == 0:
        raise CvBridgeError(f'the image is empty (shape {image.shape})')
    depth_of(image.dtype)
    return image


def channels_of(image: np.ndarray) -> int:
    """The channel count of an image array: 1 for a 2-D one, else the size of its third axis."""
    return 1 if image.ndim == 2 else image.shape[2]


def cv_type_of(image: np.ndarray) -> str:
    """The OpenCV type of an array that check_image accepted, e.g. 8UC3."""
    return f'{depth_of(image.dtype)}C{channels_of(image)}'


def rescale_depth(image: np.ndarray, dtype: np.dtype) -> np.ndarray:
    """8 <-> 16 bit with the full range kept, as upstream does (0..255 <-> 0..65535)."""
    if dtype == np.uint16:
        return image.astype(np.uint16) * np.uint16(257)
    return np.rint(image * (255 / 65535)).astype(np.uint8)


def convert(image: np.ndarray, source: Encoding, target: Encoding) -> np.ndarray:
    """image, laid out as source, in target's layout: colour order first, then depth, as upstream."""
    if source.name == target.name:
        return image
    if source.order is None or target.order is None:
        raise CvBridgeError(f'cannot convert {source.name} to {target.name}: only {", ".join(NAMED)} '
                            'convert into one another (ask for passthrough to get the data as it is)')
    if source.order != target.order:
        image = cv2.cvtColor(image, getattr(cv2, f'COLOR_{source.order}2{target.order}'))
    if source.dtype != target.dtype:
        image = rescale_depth(image, target.dtype)
    return image
