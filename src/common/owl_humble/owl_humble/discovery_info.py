"""ROS 2's graph message `rmw_dds_common/msg/ParticipantEntitiesInfo` in Humble's and Jazzy's layouts.

Every ROS 2 participant publishes one on the DDS topic `ros_discovery_info`: its gid and, per node,
the node's namespace and name and the gids of its readers and writers. The layouts differ only in
the gid: `char[24]` on Humble, `char[16]` from Iron on. DDS matches the two on the type name alone,
so each side reads the other's samples in its own layout; Humble's deserializer then sizes a
sequence from bytes that are really part of a string and allocates accordingly.

`decode` is strict (every length fits the sample, strings end in NUL, nothing but padding is left
over), so it says whether a sample would be read correctly in a given layout.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass, field
from enum import Enum

# CDR encapsulation: plain CDR, little endian, no options.
CDR_LE_HEADER = b'\x00\x01\x00\x00'
ENCAPSULATIONS = {b'\x00\x00': '>', b'\x00\x01': '<'}
MAX_NAME_LENGTH = 256  # NodeEntitiesInfo's strings are string<=256


class Layout(Enum):
    """The gid size of a distribution's rmw_dds_common/msg/Gid."""

    HUMBLE = 24
    JAZZY = 16  # Iron, Jazzy, Kilted, Rolling

    @property
    def gid_size(self) -> int:
        """The number of bytes of a gid in this layout."""
        return self.value


@dataclass
class NodeEntities:
    """One node's entry: its namespace and name, and the gids of its readers and writers."""

    namespace: str
    name: str
    reader_gids: list[bytes] = field(default_factory=list)
    writer_gids: list[bytes] = field(default_factory=list)

    @property
    def full_name(self) -> str:
        """The node's name with its namespace, as `ros2 node list` shows it."""
        return self.namespace.rstrip('/') + '/' + self.name


@dataclass
class ParticipantEntities:
    """One participant's graph message: its gid and the nodes it holds."""

    gid: bytes
    nodes: list[NodeEntities] = field(default_factory=list)

    def in_layout(self, layout: Layout) -> ParticipantEntities:
        """The same information with every gid cut or zero-padded to the layout's size.

        A GUID is 16 bytes; Humble pads it with zeros.
        """
        def fit(gid: bytes) -> bytes:
            return gid[:layout.gid_size].ljust(layout.gid_size, b'\x00')
        return ParticipantEntities(fit(self.gid), [
            NodeEntities(n.namespace, n.name, [fit(g) for g in n.reader_gids],
                         [fit(g) for g in n.writer_gids])
            for n in self.nodes])


class MalformedSample(ValueError):
    """The bytes are not a ParticipantEntitiesInfo in the layout asked for."""


class _Writer:
    def __init__(self) -> None:
        self.body = bytearray()

    def align(self, size: int) -> None:
        self.body += b'\x00' * (-len(self.body) % size)

    def u32(self, value: int) -> None:
        self.align(4)
        self.body += struct.pack('<I', value)

    def string(self, text: str) -> None:
        data = text.encode() + b'\x00'
        self.u32(len(data))
        self.body += data

    def gid(self, gid: bytes, layout: Layout) -> None:
        if len(gid) != layout.gid_size:
            raise ValueError(f'a {layout.name.title()} gid has {layout.gid_size} bytes, not {len(gid)}')
        self.body += gid

    def gids(self, gids: list[bytes], layout: Layout) -> None:
        self.u32(len(gids))
        for gid in gids:
            self.gid(gid, layout)


def encode(info: ParticipantEntities, layout: Layout) -> bytes:
    """The sample as a serialized DDS payload (encapsulation header included)."""
    out = _Writer()
    out.gid(info.gid, layout)
    out.u32(len(info.nodes))
    for node in info.nodes:
        out.string(node.namespace)
        out.string(node.name)
        out.gids(node.reader_gids, layout)
        out.gids(node.writer_gids, layout)
    out.align(4)
    return CDR_LE_HEADER + bytes(out.body)


class _Reader:
    def __init__(self, body: bytes, endian: str) -> None:
        self.body = body
        self.endian = endian
        self.at = 0

    def take(self, size: int, what: str) -> bytes:
        if size > len(self.body) - self.at:
            raise MalformedSample(f'{what} needs {size} bytes at offset {self.at}, '
                                  f'{len(self.body) - self.at} are left')
        data = self.body[self.at:self.at + size]
        self.at += size
        return data

    def u32(self, what: str) -> int:
        self.at += -self.at % 4
        return int(struct.unpack(self.endian + 'I', self.take(4, what))[0])

    def count(self, item_size: int, what: str) -> int:
        count = self.u32(what)
        if count * item_size > len(self.body) - self.at:
            raise MalformedSample(f'{what}: a sequence of {count} in {len(self.body) - self.at} bytes')
        return count

    def string(self, what: str) -> str:
        length = self.u32(what)
        if not 1 <= length <= MAX_NAME_LENGTH + 1:
            raise MalformedSample(f'{what}: a string of {length} bytes')
        data = self.take(length, what)
        if data[-1:] != b'\x00' or b'\x00' in data[:-1]:
            raise MalformedSample(f'{what}: not a NUL-terminated string')
        try:
            return data[:-1].decode()
        except UnicodeDecodeError as error:
            raise MalformedSample(f'{what}: not UTF-8 ({error.reason})') from None


def decode(data: bytes, layout: Layout) -> ParticipantEntities:
    """Read a serialized sample in the layout, or raise MalformedSample saying what does not fit."""
    endian = ENCAPSULATIONS.get(bytes(data[:2]))
    if endian is None:
        raise MalformedSample(f'encapsulation {bytes(data[:2]).hex() or "(none)"} is not plain CDR')
    body = _Reader(bytes(data[4:]), endian)
    gid = body.take(layout.gid_size, 'gid')
    # The smallest node is two empty strings and two empty sequences: 4 + 1 + pad + 4 + 1 + pad + 4 + 4.
    nodes = [NodeEntities('', '') for _ in range(body.count(20, 'node_entities_info_seq'))]
    for index, node in enumerate(nodes):
        node.namespace = body.string(f'node {index} namespace')
        node.name = body.string(f'node {index} name')
        for gids, what in ((node.reader_gids, 'reader_gid_seq'), (node.writer_gids, 'writer_gid_seq')):
            gids += [body.take(layout.gid_size, what)
                     for _ in range(body.count(layout.gid_size, f'node {index} {what}'))]
    rest = body.body[body.at:]
    if len(rest) > 3 or rest.strip(b'\x00'):
        raise MalformedSample(f'{len(rest)} bytes left over after the last node')
    return ParticipantEntities(gid, nodes)


def layout_of(data: bytes) -> Layout | None:
    """The layout the sample parses in, or None when it parses in neither."""
    for layout in Layout:
        try:
            decode(data, layout)
        except MalformedSample:
            continue
        return layout
    return None


# sizeof(rmw_dds_common::msg::NodeEntitiesInfo) on the modules' armhf (two std::string, two vectors).
NODE_ENTITIES_SIZE_ARMHF = 72


def humble_largest_allocation(data: bytes) -> int:
    """The largest block, in bytes, that Humble's generated deserializer asks for while reading the sample.

    It resizes each sequence to the length it reads before reading the elements, and stops (throws)
    only when the bytes run out. 0 for a sample too short to hold a length.
    """
    body = _Reader(bytes(data[4:]), ENCAPSULATIONS.get(bytes(data[:2]), '<'))
    largest = 0
    try:
        body.take(Layout.HUMBLE.gid_size, 'gid')
        nodes = body.u32('node_entities_info_seq')
        largest = nodes * NODE_ENTITIES_SIZE_ARMHF
        for _ in range(nodes):
            for _ in range(2):
                body.take(body.u32('string'), 'string')
            for _ in range(2):
                gids = body.u32('gid_seq')
                largest = max(largest, gids * Layout.HUMBLE.gid_size)
                body.take(gids * Layout.HUMBLE.gid_size, 'gids')
    except MalformedSample:
        pass
    return largest
