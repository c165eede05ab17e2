"""The one message codec of our pages, the server's half (the browser's half is static/socket.js).

- A text message is one JSON object with a "type". A page sends {"type": "subscribe", "id": ...,
  "channel": ..., <the channel's parameters>}, {"type": "unsubscribe", "id": ...} and
  {"type": "command", "id": ..., "name": ..., <the command's arguments>} (an action on the robot,
  e.g. the robot view's "hold_imu"; its answer is a {"type": "done", "id": ...} or an error); the server
  sends {"type": "update", "id": ..., "data": {...}} and {"type": "error", "id": ..., "error": "<one line>"}.
- A binary message is a frame: a 4-byte big-endian length, that many bytes of a JSON header (an
  "update" as above, whose data describes the payload), then the payload (an image, say).
- ROS messages travel as their fields in plain JSON (message_fields); NaN and the infinities,
  which JSON has no numbers for, as the strings "nan", "inf" and "-inf".

Everything here is node-free; what a client sends that does not fit is an ApiError whose message
is one line naming the problem.
"""

import json
import math
import struct
from typing import Any

from owl_common.hints import did_you_mean
from rosidl_runtime_py.convert import message_to_ordereddict

MAX_BODY = 1 << 20  # bytes of an HTTP request body
MAX_CLIENT_MESSAGE = 64 * 1024  # bytes of a WebSocket message from a page (subscriptions are small)
MAX_ID_LENGTH = 64
FRAME_HEADER = struct.Struct('>I')


class ApiError(Exception):
    """A request refused: an HTTP status and a one-line message for the page."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


def one_line(error: BaseException) -> str:
    """An unexpected exception as one line (its first), for a log or an 'internal error' answer."""
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def parse_json_object(data: bytes | str, what: str = 'the request body') -> dict[str, Any]:
    """A JSON object (empty input is {})."""
    if not data.strip():
        return {}
    try:
        value = json.loads(data)
    except UnicodeDecodeError:
        raise ApiError(400, f'malformed JSON in {what}: not UTF-8 text') from None
    except json.JSONDecodeError as error:
        raise ApiError(400, f'malformed JSON in {what}: {error.msg} '
                            f'(line {error.lineno}, column {error.colno})') from None
    if not isinstance(value, dict):
        raise ApiError(400, f'{what} must be a JSON object, got {type(value).__name__}')
    return value


def check_keys(body: dict[str, Any], allowed: tuple[str, ...], required: tuple[str, ...] = ()) -> None:
    """Unknown keys (with the closest allowed one) and missing required keys are errors."""
    for key in body:
        if key not in allowed:
            raise ApiError(400, f"unknown key '{key}'{did_you_mean(key, allowed)}; "
                                f"expected: {', '.join(allowed)}")
    for key in required:
        if key not in body:
            raise ApiError(400, f"missing key '{key}'")


def boolean(value: Any, what: str) -> bool:
    """Value if it is a JSON true or false, else a 400 ApiError naming `what` (no truthy numbers)."""
    if not isinstance(value, bool):
        raise ApiError(400, f'{what} must be true or false, got {json.dumps(value)}')
    return value


def decode_client_message(text: str) -> dict[str, Any]:
    """A page's WebSocket message: a JSON object with a string "type" and, if given, a valid "id"."""
    size = len(text.encode())
    if size > MAX_CLIENT_MESSAGE:
        raise ApiError(413, f'message of {size} bytes is over the limit of {MAX_CLIENT_MESSAGE}')
    message = parse_json_object(text, 'the message')
    kind = message.get('type')
    if not isinstance(kind, str) or not kind:
        raise ApiError(400, f'the message needs a "type" string, got {json.dumps(kind)}')
    if 'id' in message:
        message_id(message['id'])
    return message


def message_id(value: Any) -> int | str:
    """A subscription's id as the page chose it: a number or a short string."""
    if isinstance(value, bool) or not isinstance(value, (int, str)) or \
            (isinstance(value, str) and not 0 < len(value) <= MAX_ID_LENGTH):
        raise ApiError(400, f'"id" must be a number or a string of 1 to {MAX_ID_LENGTH} characters, '
                            f'got {json.dumps(value)[:80]}')
    return value


def encode(message: dict[str, Any]) -> str:
    """A message as compact JSON text (NaN and infinities as strings, see json_safe)."""
    return json.dumps(json_safe(message), separators=(',', ':'), allow_nan=False)


def update(subscription_id: int | str, data: dict[str, Any]) -> dict[str, Any]:
    """The "update" message that carries new data to a subscription."""
    return {'type': 'update', 'id': subscription_id, 'data': data}


def done(command_id: int | str | None, result: dict[str, Any] | None = None) -> dict[str, Any]:
    """The "done" message: the command with this id was carried out, with what came of it if it says."""
    message: dict[str, Any] = {'type': 'done', 'id': command_id}
    if result is not None:
        message['result'] = result
    return message


def error(subscription_id: int | str | None, message: str) -> dict[str, Any]:
    """The "error" message: one line for the subscription or command with this id (None: no id)."""
    return {'type': 'error', 'id': subscription_id, 'error': message}


def pack_frame(header: dict[str, Any], payload: bytes) -> bytes:
    """A binary message: header length, JSON header, payload."""
    header_bytes = encode(header).encode()
    return FRAME_HEADER.pack(len(header_bytes)) + header_bytes + payload


def unpack_frame(frame: bytes) -> tuple[dict[str, Any], bytes]:
    """(header, payload) of a binary message made by pack_frame."""
    if len(frame) < FRAME_HEADER.size:
        raise ApiError(400, f'a frame of {len(frame)} bytes has no header length')
    (length,) = FRAME_HEADER.unpack_from(frame)
    end = FRAME_HEADER.size + length
    if end > len(frame):
        raise ApiError(400, f'a frame of {len(frame)} bytes announces a header of {length} bytes')
    return parse_json_object(frame[FRAME_HEADER.size:end], 'the frame header'), frame[end:]


def json_safe(value: Any) -> Any:
    """Plain data JSON can carry: NaN and infinities become the strings 'nan', 'inf', '-inf'."""
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, dict):
        return {key: json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(item) for item in value]
    return value


def message_fields(message: Any) -> dict[str, Any]:
    """A ROS message's values as JSON-safe nested dicts and lists, in declaration order."""
    return json_safe(message_to_ordereddict(message))


QUATERNION_KEYS = ('x', 'y', 'z', 'w')
QUATERNION_NORM_TOLERANCE = 0.01  # a page's float32/float64 rounding, not a different rotation


def unit_quaternion(value: Any, what: str = 'the orientation') -> tuple[float, float, float, float]:
    """(x, y, z, w) of a rotation sent as {"x", "y", "z", "w"}, returned normalised.

    The parts must be finite numbers of norm 1 (within QUATERNION_NORM_TOLERANCE); anything else is a
    one-line ApiError.
    """
    if not isinstance(value, dict):
        raise ApiError(400, f'{what} must be an object {{"x", "y", "z", "w"}}, got {json.dumps(value)[:80]}')
    check_keys(value, QUATERNION_KEYS, required=QUATERNION_KEYS)
    parts = []
    for key in QUATERNION_KEYS:
        part = value[key]
        if isinstance(part, bool) or not isinstance(part, (int, float)):
            raise ApiError(400, f'{what}: "{key}" must be a number, got {json.dumps(part)[:80]}')
        if not math.isfinite(part):
            raise ApiError(400, f'{what}: "{key}" must be finite, got {part}')
        parts.append(float(part))
    norm = math.sqrt(sum(part * part for part in parts))
    if abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE:
        raise ApiError(400, f'{what} must be a unit quaternion (norm 1), got norm {norm:.6g}')
    x, y, z, w = (part / norm for part in parts)
    return x, y, z, w
