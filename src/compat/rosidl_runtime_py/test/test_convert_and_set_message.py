"""The message library without ROS communication: YAML/CSV/dicts as upstream, input with clear errors."""

from collections import OrderedDict

import pytest
from geometry_msgs.msg import PoseArray, Twist, Vector3
from rcl_interfaces.msg import ParameterDescriptor
from rosidl_runtime_py import message_to_csv, message_to_ordereddict, message_to_yaml, set_message_fields
from rosidl_runtime_py.set_message import FieldError, parse_yaml
from sensor_msgs.msg import Imu
from std_msgs.msg import Bool, ByteMultiArray, Header, String, UInt8


def filled(message, values):
    set_message_fields(message, values)
    return message


def test_yaml_keeps_declaration_order_and_block_style():
    twist = Twist(linear=Vector3(x=2.0), angular=Vector3(z=1.8))
    assert message_to_yaml(twist) == ('linear:\n  x: 2.0\n  y: 0.0\n  z: 0.0\n'
                                      'angular:\n  x: 0.0\n  y: 0.0\n  z: 1.8\n')


def test_yaml_scalars_and_sequences():
    assert message_to_yaml(String(data='Hello World: 1')) == "data: 'Hello World: 1'\n"
    assert message_to_yaml(String(data='')) == "data: ''\n"
    poses = filled(PoseArray(), {'poses': [{'position': {'x': 1}}]})
    text = message_to_yaml(poses)
    assert 'poses:\n- position:\n    x: 1.0\n' in text
    assert message_to_yaml(PoseArray()).endswith('poses: []\n')
    two_bytes = filled(ByteMultiArray(), {'data': [1, 2]})
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
    numbers = filled(ByteMultiArray(), {'data': [1, 2, 3]})
    assert message_to_yaml(numbers, truncate_length=2).endswith("- '...'\n")


def test_header_auto_is_expanded_only_when_asked_for():
    from builtin_interfaces.msg import Time
    from geometry_msgs.msg import PointStamped
    point = PointStamped()
    stamps = set_message_fields(point, {'header': 'auto'}, expand_header_auto=True)
    stamps[0](Time(sec=7))
    assert point.header.stamp.sec == 7
    with pytest.raises(FieldError, match="field 'header' must be a mapping"):
        set_message_fields(PointStamped(), {'header': 'auto'}, expand_time_now=True)


def test_ordereddict_is_in_declaration_order_and_nested():
    values = message_to_ordereddict(Twist(linear=Vector3(x=1.0)))
    assert isinstance(values, OrderedDict)
    assert list(values) == ['linear', 'angular']
    assert values['linear'] == {'x': 1.0, 'y': 0.0, 'z': 0.0}
    assert message_to_ordereddict(String(data='abcdef'), truncate_length=3) == {'data': 'abc...'}


def test_csv_flattens_leaves():
    assert message_to_csv(Twist(linear=Vector3(x=1.5))) == '1.5,0.0,0.0,0.0,0.0,0.0'
    assert message_to_csv(String(data='a b')) == 'a b'


def test_fill_converts_ints_to_floats_and_nested_messages():
    twist = filled(Twist(), parse_yaml('{linear: {x: 2}, angular: {z: 1}}'))
    assert twist.linear.x == 2.0
    assert twist.angular.z == 1.0
    assert filled(UInt8(), {'data': 255.0}).data == 255
    assert filled(String(), {'data': 5}).data == '5'
    assert filled(Twist(), None) == Twist()


def test_header_auto_and_stamp_now_are_refreshed_before_each_publish():
    from builtin_interfaces.msg import Time
    header = Header()
    stamps = set_message_fields(header, {'stamp': 'now', 'frame_id': 'map'}, expand_time_now=True)
    assert len(stamps) == 1
    stamps[0](Time(sec=3, nanosec=4))
    assert (header.stamp.sec, header.stamp.nanosec, header.frame_id) == (3, 4, 'map')
    with pytest.raises(FieldError, match="field 'stamp' must be a mapping"):
        set_message_fields(Header(), {'stamp': 'now'})  # only when asked for, as upstream


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
        filled(message, values)
    assert error in str(caught.value)
    assert '\n' not in str(caught.value)


def test_invalid_yaml_is_one_line():
    with pytest.raises(FieldError, match=r"invalid YAML \(line 1, column 16\): expected ',' or '\}'"):
        parse_yaml('{linear: {x: 1}')
