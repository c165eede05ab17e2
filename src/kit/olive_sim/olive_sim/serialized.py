"""A serialized ROS message whose stamp and float64 fields are rewritten in place, free of ROS.

Publishing a message object makes rclpy convert every field (nested messages, covariance arrays)
to C on each call; at 100 Hz that was the largest part of an IMU's CPU. The bytes of a fixed-shape
message (same frame_id, names and array lengths every time) differ only in the values, so the node
serializes one template in which each changing field holds a distinct marker value, this class
finds where each marker sits, and every publication patches those places and publishes the bytes.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence

# header.stamp markers: an unlikely (sec, nanosec) pair that locates the stamp in the template.
STAMP_MARKER = (1_234_567_891, 987_654_321)
_DOUBLE = struct.Struct('=d')  # serializers write the host's byte order (the header says which)
_STAMP = struct.Struct('=iI')


def markers(count: int) -> list[float]:
    """`count` (up to 1024) distinct float64 values that no reading or constant field would have."""
    if not 0 <= count <= 1024:
        raise ValueError(f'at most 1024 markers, not {count}')
    return [-(2.0 ** 1000) * (1.0 + index / 1024) for index in range(count)]


class SerializedTemplate:
    """Fills a serialized message's stamp and float64 fields without rebuilding the message."""

    def __init__(self, template: bytes, fields: Sequence[float]) -> None:
        self._buffer = bytearray(template)
        self._stamp = self._find(_STAMP.pack(*STAMP_MARKER), 'the stamp marker')
        self._offsets = [self._find(_DOUBLE.pack(value), f'marker {value!r}') for value in fields]

    def _find(self, pattern: bytes, what: str) -> int:
        offset = self._buffer.find(pattern)
        if offset < 0 or self._buffer.find(pattern, offset + 1) >= 0:
            raise ValueError(f'{what} must occur exactly once in the serialized template')
        return offset

    def fill(self, nanoseconds: int, values: Sequence[float]) -> bytes:
        """The message stamped `nanoseconds` (since the epoch) with the fields set to `values`."""
        buffer = self._buffer
        _STAMP.pack_into(buffer, self._stamp, *divmod(nanoseconds, 1_000_000_000))
        pack = _DOUBLE.pack_into
        for offset, value in zip(self._offsets, values, strict=True):
            pack(buffer, offset, value)
        return bytes(buffer)


# Encapsulation identifiers (first two bytes, big-endian) of plain CDR, the classic XCDR1 layout
# ROS 2's Fast DDS writes: 8-byte values are 8-aligned, offsets count from after the 4-byte header.
_PLAIN_CDR = {b'\x00\x00': '>', b'\x00\x01': '<'}


def joint_state_position(serialized: bytes) -> float | None:
    """position[0] of a serialized sensor_msgs/JointState, None when it has no position.

    Reading the one value the camera needs straight from the bytes spares building the whole
    message (names, three arrays) 200 times a second. ValueError for encodings other than plain CDR
    or for truncated data; the caller then deserializes the message as usual.
    """
    order = _PLAIN_CDR.get(serialized[:2])
    if order is None:
        raise ValueError(f'not plain CDR (encapsulation {serialized[:2].hex()})')
    data = memoryview(serialized)[4:]
    count = struct.Struct(order + 'I')

    def read_count(offset: int) -> tuple[int, int]:
        offset += -offset % 4
        return count.unpack_from(data, offset)[0], offset + 4

    try:
        length, offset = read_count(8)              # header.frame_id, after the stamp
        names, offset = read_count(offset + length)
        for _ in range(names):
            length, offset = read_count(offset)
            offset += length
        positions, offset = read_count(offset)
        if positions == 0:
            return None
        offset += -offset % 8
        return struct.unpack_from(order + 'd', data, offset)[0]
    except struct.error as error:
        raise ValueError(f'truncated JointState: {error}') from None
