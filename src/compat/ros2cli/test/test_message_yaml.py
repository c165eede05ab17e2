"""The message codec without ROS communication: YAML/CSV output as upstream, input with clear errors."""

import pytest
from geometry_msgs.msg import PoseArray, Twist, Vector3
from rcl_interfaces.msg import ParameterDescriptor
from ros2cli.message_yaml import (
    FieldError,
    fill_message,
    message_to_csv,
    message_to_yaml,
    parse_yaml,
)
from sensor_msgs.msg import Imu
from std_msgs.msg import Bool, ByteMultiArray, Header, String, UInt8


def test_yaml_keeps_declaration_order_and_block_style():
    twist = Twist(linear=Vector3(x=2.0), angular=Vector3(z=1.8))
    assert message_to_yaml(twist) == ('linear:\n  x: 2.0\n  y: 0.0\n  z: 0.0\n'
                                      'angular:\n  x: 0.0\n  y: 0.0\n  z: 1.8\n')


def test_yaml_scalars_and_sequences():
    assert message_to_yaml(String(data='Hello World: 1')) == "data: 'Hello World: 1'\n"
    assert message_to_yaml(String(data='')) == "data: ''\n"
    poses = fill_message(PoseArray(), {'poses': [{'position': {'x': 1}}]})
    text = message_to_yaml(poses)
    assert 'poses:\n- position:\n    x: 1.0\n' in text
    assert message_to_yaml(PoseArray()).endswith('poses: []\n')
    two_bytes = fill_message(ByteMultiArray(), {'data': [1, 2]})
    assert message_to_yaml(two_bytes).endswith('data:\n- "\\x01"\n- "\\x02"\n')


def test_flow_style_applies_to_lists_only():
    text = message_to_yaml(Imu(), flow_style=True)
    assert 'orientation_covariance: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n' in text
    assert text.startswith('header:\n  stamp:\n')


def test_placeholders_and_truncation():
    imu = message_to_yaml(Imu(), no_arr=True)
    assert "orientation_covariance: '<array type: double[9]>'" in imu
    descriptor = message_to_yaml(ParameterDescriptor(), no_arr=True)
    assert "integer_range: '<sequence type: rcl_interfaces/msg/IntegerRange[1], length: 0>'" in descriptor
    assert message_to_yaml(PoseArray(), no_arr=True).endswith(
        "poses: '<sequence type: geometry_msgs/msg/Pose, length: 0>'\n")
    assert message_to_yaml(String(data='hello'), no_str=True) == "data: '<string length: <5>>'\n"
    assert message_to_yaml(String(data='Hello World'), truncate_length=5) == 'data: Hello...\n'
    numbers = fill_message(ByteMultiArray(), {'data': [1, 2, 3]})
    assert message_to_yaml(numbers, truncate_length=2).endswith("- '...'\n")


def test_csv_flattens_leaves():
    assert message_to_csv(Twist(linear=Vector3(x=1.5))) == '1.5,0.0,0.0,0.0,0.0,0.0'
    assert message_to_csv(String(data='a b')) == 'a b'


def test_fill_converts_ints_to_floats_and_nested_messages():
    twist = fill_message(Twist(), parse_yaml('{linear: {x: 2}, angular: {z: 1}}'))
    assert twist.linear.x == 2.0 and twist.angular.z == 1.0
    assert fill_message(UInt8(), {'data': 255.0}).data == 255
    assert fill_message(String(), {'data': 5}).data == '5'
    assert fill_message(Twist(), None) == Twist()


def test_header_auto_and_stamp_now_are_refreshed_before_each_publish():
    from builtin_interfaces.msg import Time
    stamps = []
    header = fill_message(Header(), {'stamp': 'now', 'frame_id': 'map'}, stamps)
    assert len(stamps) == 1
    stamps[0](Time(sec=3, nanosec=4))
    assert (header.stamp.sec, header.stamp.nanosec, header.frame_id) == (3, 4, 'map')
    with pytest.raises(FieldError, match="field 'stamp' must be a mapping"):
        fill_message(Header(), {'stamp': 'now'})  # only topic pub passes `stamps`


@pytest.mark.parametrize(('message', 'values', 'error'), [
    (Twist(), {'linaer': {}}, "unknown field 'linaer' (did you mean 'linear'?); geometry_msgs/msg/Twist has: "
                              'linear, angular'),
    (Twist(), {'linear': {'q': 1}}, "unknown field 'linear.q'"),
    (Twist(), {'linear': {'x': 'fast'}}, "field 'linear.x' expects a number (double), got 'fast' (str)"),
    (Twist(), {'linear': 3}, "field 'linear' must be a mapping of geometry_msgs/msg/Vector3 fields, got 3"),
    (Twist(), [1, 2], 'the values must be a mapping of geometry_msgs/msg/Twist fields'),
    (UInt8(), {'data': 256}, "field 'data' expects a uint8 in [0, 255], got 256"),
    (UInt8(), {'data': 2.5}, "field 'data' expects an integer (uint8), got 2.5"),
    (Bool(), {'data': 'yes please'}, "field 'data' expects a boolean (true/false)"),
    (Imu(), {'orientation_covariance': [1.0]}, "field 'orientation_covariance' expects exactly 9 elements"),
    (ParameterDescriptor(), {'integer_range': [{}, {}]}, "field 'integer_range' takes at most 1 elements"),
    (PoseArray(), {'poses': [{'position': {'x': 'a'}}]}, "field 'poses[0].position.x' expects a number"),
    (String(), {'data': [1]}, "field 'data' expects a string"),
])
def test_fill_errors_name_the_field(message, values, error):
    with pytest.raises(FieldError) as caught:
        fill_message(message, values)
    assert error in str(caught.value)
    assert '\n' not in str(caught.value)


def test_invalid_yaml_is_one_line():
    with pytest.raises(FieldError, match=r"invalid YAML \(line 1, column 16\): expected ',' or '\}'"):
        parse_yaml('{linear: {x: 1}')
