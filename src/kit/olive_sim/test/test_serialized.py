"""Serialized templates: the filled bytes are what serializing the filled message would give."""

import struct

import pytest
from olive_sim.serialized import STAMP_MARKER, SerializedTemplate, joint_state_position, markers
from rclpy.serialization import deserialize_message, serialize_message
from sensor_msgs.msg import Imu, JointState


def test_markers_are_distinct_and_far_from_real_values():
    values = markers(16)
    assert len(set(values)) == 16
    assert all(v < -1e299 for v in values)
    with pytest.raises(ValueError, match='at most 1024'):
        markers(1025)


def joint_state(stamp, position, velocity, effort):
    msg = JointState(name=['pan_joint'], position=[position], velocity=[velocity], effort=[effort])
    msg.header.stamp.sec, msg.header.stamp.nanosec = stamp
    msg.header.frame_id = 'pan_rotor_link'
    return msg


def test_a_filled_joint_state_serializes_like_the_message():
    values = markers(3)
    template = SerializedTemplate(serialize_message(joint_state(STAMP_MARKER, *values)), values)
    filled = deserialize_message(template.fill(1_700_000_000_250_000_000, (0.5, -1.25, 0.03)), JointState)
    # Compared as messages: the rmw serializer pads a JointState with a few uninitialised bytes.
    assert filled == joint_state((1_700_000_000, 250_000_000), 0.5, -1.25, 0.03)
    # The template is reused: a second fill replaces every value.
    again = deserialize_message(template.fill(5, (1.0, 2.0, 3.0)), JointState)
    assert (again.header.stamp.sec, again.header.stamp.nanosec) == (0, 5)
    assert [list(again.position), list(again.velocity), list(again.effort)] == [[1.0], [2.0], [3.0]]
    assert list(again.name) == ['pan_joint']
    assert again.header.frame_id == 'pan_rotor_link'


def test_an_imu_keeps_its_constant_fields():
    values = markers(4)
    imu = Imu()
    imu.header.stamp.sec, imu.header.stamp.nanosec = STAMP_MARKER
    o = imu.orientation
    o.x, o.y, o.z, o.w = values
    imu.orientation_covariance = [4e-6, 0.0, 0.0, 0.0, 4e-6, 0.0, 0.0, 0.0, 4e-6]
    filled = deserialize_message(SerializedTemplate(serialize_message(imu), values).fill(
        2_000_000_001, (0.0, 0.0, 0.6, 0.8)), Imu)
    assert (filled.orientation.z, filled.orientation.w) == (0.6, 0.8)
    assert filled.orientation_covariance[4] == 4e-6
    assert (filled.header.stamp.sec, filled.header.stamp.nanosec) == (2, 1)


def test_a_marker_must_occur_exactly_once():
    stamp = struct.pack('=iI', *STAMP_MARKER)
    twice = struct.pack('=d', 1.5) * 2
    with pytest.raises(ValueError, match='exactly once'):
        SerializedTemplate(stamp + twice, [1.5])
    with pytest.raises(ValueError, match='stamp marker'):
        SerializedTemplate(twice, [1.5])
    with pytest.raises(ValueError, match='exactly once'):
        SerializedTemplate(stamp + twice, [2.5])


def test_fill_needs_one_value_per_field():
    template = SerializedTemplate(struct.pack('=iId', *STAMP_MARKER, 1.5), [1.5])
    with pytest.raises(ValueError, match='argument 2 is longer than argument 1'):
        template.fill(0, (1.0, 2.0))


@pytest.mark.parametrize(('names', 'positions', 'frame_id'), [
    (['pan_joint'], [0.75], 'pan_rotor_link'),
    (['a', 'bb', 'ccc'], [-1.5, 2.0, 3.0], ''),
    ([], [1e-300], 'x' * 7),
    (['tilt_joint'], [], 'f'),
])
def test_joint_state_position_reads_the_first_position_from_the_bytes(names, positions, frame_id):
    msg = JointState(name=names, position=positions, velocity=[0.5] * len(positions))
    msg.header.frame_id = frame_id
    msg.header.stamp.sec = 3
    expected = positions[0] if positions else None
    assert joint_state_position(serialize_message(msg)) == expected


def test_joint_state_position_refuses_other_encodings_and_truncated_data():
    data = serialize_message(JointState(name=['pan_joint'], position=[0.75]))
    with pytest.raises(ValueError, match='not plain CDR'):
        joint_state_position(b'\x00\x07' + data[2:])
    with pytest.raises(ValueError, match='truncated'):
        joint_state_position(data[:data.index(struct.pack('=d', 0.75)) + 4])  # into the position
