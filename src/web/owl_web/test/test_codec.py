"""The message codec: what pages send, what the server sends, each refusal one line."""

import math

import pytest
from owl_web import codec
from owl_web.codec import ApiError
from std_msgs.msg import Float64


def refused(call, *args) -> ApiError:
    with pytest.raises(ApiError) as caught:
        call(*args)
    assert caught.value.message
    assert '\n' not in caught.value.message
    return caught.value


def test_json_bodies():
    assert codec.parse_json_object(b'') == {}
    assert codec.parse_json_object(b'{"rate": 2}') == {'rate': 2}
    error = refused(codec.parse_json_object, b'{"rate": }')
    assert (error.status, error.message) == (400, 'malformed JSON in the request body: Expecting value '
                                                  '(line 1, column 10)')
    assert refused(codec.parse_json_object, b'[1, 2]').message == \
        'the request body must be a JSON object, got list'
    assert refused(codec.parse_json_object, b'\xff\xfe').status == 400


def test_keys_and_flags():
    codec.check_keys({'topic': '/a'}, ('topic', 'rate'), required=('topic',))
    assert refused(codec.check_keys, {'topic': '/a', 'rte': 1}, ('topic', 'rate')).message == \
        "unknown key 'rte' (did you mean 'rate'?); expected: topic, rate"
    assert refused(codec.check_keys, {}, ('topic',), ('topic',)).message == "missing key 'topic'"
    assert codec.boolean(False, 'enabled') is False
    assert refused(codec.boolean, 'yes', 'enabled').message == 'enabled must be true or false, got "yes"'


def test_client_messages():
    assert codec.decode_client_message('{"type": "subscribe", "id": 3, "channel": "graph"}') == \
        {'type': 'subscribe', 'id': 3, 'channel': 'graph'}
    assert codec.decode_client_message('{"type": "unsubscribe", "id": "images"}')['id'] == 'images'
    decode = codec.decode_client_message
    assert refused(decode, '{"type": ').message.startswith('malformed JSON in the message: ')
    assert refused(decode, '{"id": 1}').message == 'the message needs a "type" string, got null'
    assert refused(decode, '{"type": 7}').message == 'the message needs a "type" string, got 7'
    assert refused(codec.decode_client_message, '{"type": "subscribe", "id": true}').message == \
        '"id" must be a number or a string of 1 to 64 characters, got true'
    assert refused(codec.decode_client_message, '{"type": "subscribe", "id": ""}').status == 400
    big = '{"type": "subscribe", "pad": "' + 'x' * codec.MAX_CLIENT_MESSAGE + '"}'
    error = refused(codec.decode_client_message, big)
    assert (error.status, error.message) == (413, f'message of {len(big)} bytes is over the limit of 65536')


def test_server_messages_and_frames():
    assert codec.encode(codec.update(1, {'x': math.nan})) == '{"type":"update","id":1,"data":{"x":"nan"}}'
    assert codec.encode(codec.error(None, 'bad')) == '{"type":"error","id":null,"error":"bad"}'
    frame = codec.pack_frame(codec.update('cam', {'frame': 4}), b'\xff\xd8\xff jpeg')
    assert frame[:4] == len(codec.encode(codec.update('cam', {'frame': 4}))).to_bytes(4, 'big')
    assert codec.unpack_frame(frame) == ({'type': 'update', 'id': 'cam', 'data': {'frame': 4}},
                                         b'\xff\xd8\xff jpeg')
    assert refused(codec.unpack_frame, b'\x00\x00').message == 'a frame of 2 bytes has no header length'
    assert refused(codec.unpack_frame, b'\x00\x00\x00\x09{}').message == \
        'a frame of 6 bytes announces a header of 9 bytes'


def test_ros_messages_as_json():
    assert codec.message_fields(Float64(data=math.inf)) == {'data': 'inf'}
    assert codec.json_safe({'a': [math.nan, 1.0], 'b': -math.inf}) == {'a': ['nan', 1.0], 'b': '-inf'}
    assert codec.one_line(ValueError('first\nsecond')) == 'first'
    assert codec.one_line(KeyError()) == 'KeyError'


def test_unit_quaternions():
    assert codec.unit_quaternion({'x': 0, 'y': 0, 'z': 0, 'w': 1.005}) == pytest.approx((0, 0, 0, 1))
    for value, error in [
            ([0, 0, 0, 1], 'the orientation must be an object {"x", "y", "z", "w"}, got [0, 0, 0, 1]'),
            ({'x': 0, 'y': 0, 'z': 0}, "missing key 'w'"),
            ({'x': 0, 'y': 0, 'z': 0, 'w': 1, 'v': 0}, "unknown key 'v'; expected: x, y, z, w"),
            ({'x': True, 'y': 0, 'z': 0, 'w': 1}, 'the orientation: "x" must be a number, got true'),
            ({'x': 0, 'y': math.inf, 'z': 0, 'w': 1}, 'the orientation: "y" must be finite, got inf'),
            ({'x': 0, 'y': 0, 'z': 0, 'w': 0},
             'the orientation must be a unit quaternion (norm 1), got norm 0')]:
        with pytest.raises(ApiError) as refused:
            codec.unit_quaternion(value)
        assert refused.value.message == error
        assert refused.value.status == 400
