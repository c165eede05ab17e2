"""The graph message in Humble's and Jazzy's layouts: round trips, strict reading, misreadings."""

import pytest
from owl_humble import discovery_info as info
from owl_humble.discovery_info import Layout

GUID = bytes(range(1, 13)) + b'\x00\x00\x01\xc1'


def sample(layout: Layout, nodes: int = 2) -> info.ParticipantEntities:
    entities = info.ParticipantEntities(GUID, [
        info.NodeEntities('/', f'node{index}', [GUID[:12] + bytes([0, 0, index, 4])],
                          [GUID[:12] + bytes([0, 0, index, 3]), GUID[:12] + bytes([0, 1, index, 3])])
        for index in range(nodes)])
    return entities.in_layout(layout)


@pytest.mark.parametrize('layout', list(Layout))
@pytest.mark.parametrize('nodes', [0, 1, 3])
def test_a_sample_reads_back_in_its_own_layout(layout, nodes):
    entities = sample(layout, nodes)
    data = info.encode(entities, layout)
    assert data[:4] == b'\x00\x01\x00\x00'
    assert len(data) % 4 == 0
    assert info.decode(data, layout) == entities
    assert info.layout_of(data) is layout


def test_humble_pads_the_16_byte_guid_with_zeros_and_jazzy_cuts_it_back():
    humble = sample(Layout.HUMBLE)
    assert humble.gid == GUID + bytes(8)
    assert humble.in_layout(Layout.JAZZY) == sample(Layout.JAZZY)
    assert humble.nodes[0].full_name == '/node0'
    assert info.NodeEntities('/ns/', 'n').full_name == '/ns/n'


@pytest.mark.parametrize('nodes', [1, 3])
def test_a_jazzy_sample_does_not_parse_in_humble_layout_and_humble_would_reserve_a_lot(nodes):
    data = info.encode(sample(Layout.JAZZY, nodes), Layout.JAZZY)
    with pytest.raises(info.MalformedSample):
        info.decode(data, Layout.HUMBLE)
    assert info.humble_largest_allocation(data) > 1000


def test_a_humble_sample_read_in_jazzy_layout_has_trailing_bytes():
    # Jazzy's (non-strict) reader takes the gid right and reads no node: the zero padding is the count.
    data = info.encode(sample(Layout.HUMBLE, 0), Layout.HUMBLE)
    with pytest.raises(info.MalformedSample, match='left over'):
        info.decode(data, Layout.JAZZY)


@pytest.mark.parametrize(('data', 'problem'), [
    (b'', 'encapsulation'),
    (b'\x00\x07\x00\x00' + bytes(24), 'encapsulation'),
    (b'\x00\x01\x00\x00' + bytes(10), 'gid needs'),
    (b'\x00\x01\x00\x00' + bytes(16) + b'\xff\xff\xff\x7f', 'a sequence of'),
    (b'\x00\x01\x00\x00' + bytes(16) + b'\x01\x00\x00\x00' + b'\x00\x00\x00\x00' + bytes(20), 'string of 0'),
    (b'\x00\x01\x00\x00' + bytes(16) + b'\x01\x00\x00\x00' + b'\x02\x00\x00\x00/x' + bytes(18), 'NUL'),
    (b'\x00\x01\x00\x00' + bytes(16) + b'\x01\x00\x00\x00' + b'\x02\x00\x00\x00\xff\x00' + bytes(18),
     'UTF-8'),
])
def test_bytes_that_are_no_sample_say_why(data, problem):
    with pytest.raises(info.MalformedSample, match=problem):
        info.decode(data, Layout.JAZZY)
    assert info.layout_of(data) is None


def test_big_endian_samples_are_read_too():
    little = info.encode(sample(Layout.JAZZY, 0), Layout.JAZZY)
    big = b'\x00\x00\x00\x00' + little[4:]  # no node: only the count changes, and it is 0
    assert info.decode(big, Layout.JAZZY).gid == GUID


def test_a_gid_of_the_wrong_size_is_refused_when_encoding():
    with pytest.raises(ValueError, match='Humble gid has 24 bytes, not 16'):
        info.encode(info.ParticipantEntities(GUID), Layout.HUMBLE)
