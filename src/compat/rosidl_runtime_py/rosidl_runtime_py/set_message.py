"""Filling a message from plain data (parsed YAML), as upstream rosidl_runtime_py.set_message does.

Its errors take one line, naming the field, the expected type and the closest valid field name.

Stricter than upstream where upstream silently changes a value: integers refuse non-integral numbers
(upstream truncates 2.7 to 2), booleans refuse strings (upstream makes 'false' True), numbers are
range-checked.
"""

import importlib
from collections.abc import Callable
from typing import Any

import yaml
from owl_common.hints import did_you_mean
from rosidl_parser.definition import (
    AbstractGenericString,
    AbstractNestedType,
    Array,
    BoundedSequence,
    BoundedString,
    BoundedWString,
    NamespacedType,
)

from rosidl_runtime_py.convert import fields_of, type_text
from rosidl_runtime_py.utilities import type_name_of

INTEGER_RANGES = {
    'int8': (-2**7, 2**7 - 1), 'uint8': (0, 2**8 - 1), 'int16': (-2**15, 2**15 - 1),
    'uint16': (0, 2**16 - 1), 'int32': (-2**31, 2**31 - 1), 'uint32': (0, 2**32 - 1),
    'int64': (-2**63, 2**63 - 1), 'uint64': (0, 2**64 - 1), 'octet': (0, 255),
    'short': (-2**15, 2**15 - 1), 'unsigned short': (0, 2**16 - 1),
    'long': (-2**31, 2**31 - 1), 'unsigned long': (0, 2**32 - 1),
    'long long': (-2**63, 2**63 - 1), 'unsigned long long': (0, 2**64 - 1),
}
FLOAT_TYPES = ('float', 'double', 'long double')


class FieldError(ValueError):
    """Values that do not fit a message; str() is one line naming the field and the problem."""



def parse_yaml(text: str) -> Any:
    """yaml.safe_load with a one-line FieldError for malformed text."""
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, 'problem_mark', None)
        where = f' (line {mark.line + 1}, column {mark.column + 1})' if mark else ''
        problem = getattr(error, 'problem', None) or str(error).splitlines()[0]
        raise FieldError(f'invalid YAML{where}: {problem}: {text!r}') from None


def _describe(value: Any) -> str:
    return f'{value!r} ({type(value).__name__})'


def _convert_basic(value: Any, typename: str, path: str) -> Any:
    if typename == 'boolean':
        if isinstance(value, bool):
            return value
        if isinstance(value, int) and value in (0, 1):
            return bool(value)
        raise FieldError(f"field '{path}' expects a boolean (true/false), got {_describe(value)}")
    if typename in FLOAT_TYPES:
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        raise FieldError(f"field '{path}' expects a number ({typename}), got {_describe(value)}")
    if typename == 'octet':
        if isinstance(value, (bytes, str)) and len(value) == 1:
            return value.encode('latin-1') if isinstance(value, str) else value
        number = _integer(value, typename, path)
        return bytes([number])
    if typename in ('char', 'wchar'):
        if isinstance(value, str) and len(value) == 1:
            return value
        raise FieldError(f"field '{path}' expects a single character, got {_describe(value)}")
    return _integer(value, typename, path)


def _integer(value: Any, typename: str, path: str) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if not isinstance(value, int) or isinstance(value, bool):
        raise FieldError(f"field '{path}' expects an integer ({typename}), got {_describe(value)}")
    low, high = INTEGER_RANGES.get(typename, (-2**63, 2**64 - 1))
    if not low <= value <= high:
        raise FieldError(f"field '{path}' expects a {typename} in [{low}, {high}], got {value}")
    return value


def _convert_string(value: Any, slot_type: Any, path: str) -> str:
    if isinstance(value, (dict, list)):
        raise FieldError(f"field '{path}' expects a string, got {_describe(value)}")
    text = value if isinstance(value, str) else str(value).lower() if isinstance(value, bool) \
        else str(value)
    if isinstance(slot_type, (BoundedString, BoundedWString)) and len(text) > slot_type.maximum_size:
        raise FieldError(f"field '{path}' is limited to {slot_type.maximum_size} characters, "
                         f'got {len(text)}')
    return text


StampSetter = Callable[[Any], None]  # called with the time `now` before each publish


class _Stamps:
    """Which time keywords are accepted, and the setters of the fields that used one."""

    def __init__(self, header_auto: bool, time_now: bool) -> None:
        self.header_auto, self.time_now = header_auto, time_now
        self.setters: list[StampSetter] = []


def _convert(value: Any, slot_type: Any, current: Any, path: str,
             stamps: _Stamps | None) -> Any:
    if isinstance(slot_type, AbstractNestedType):
        if not isinstance(value, list):
            raise FieldError(f"field '{path}' expects a list of {type_text(slot_type)}, "
                             f'got {_describe(value)}')
        if isinstance(slot_type, Array) and len(value) != slot_type.size:
            raise FieldError(f"field '{path}' expects exactly {slot_type.size} elements, "
                             f'got {len(value)}')
        if isinstance(slot_type, BoundedSequence) and len(value) > slot_type.maximum_size:
            raise FieldError(f"field '{path}' takes at most {slot_type.maximum_size} elements, "
                             f'got {len(value)}')
        element_type = slot_type.value_type
        element_class = None
        if isinstance(element_type, NamespacedType):
            module = importlib.import_module('.'.join(element_type.namespaces))
            element_class = getattr(module, element_type.name)
        converted = [
            _convert(item, element_type, element_class() if element_class else None,
                     f'{path}[{i}]', stamps)
            for i, item in enumerate(value)]
        return converted
    if isinstance(slot_type, NamespacedType):
        if stamps is not None and isinstance(value, str):
            stamp = _stamp_keyword(value, slot_type, current, path, stamps)
            if stamp is not None:
                return stamp
        return _fill(type(current)(), value, path, stamps)
    if isinstance(slot_type, AbstractGenericString):
        return _convert_string(value, slot_type, path)
    return _convert_basic(value, slot_type.typename, path)


def _stamp_keyword(value: str, slot_type: Any, current: Any, path: str, stamps: _Stamps) -> Any:
    """`header: auto` / `stamp: now` (topic pub): the time is written before every publish."""
    name = '/'.join([*slot_type.namespaces, slot_type.name])
    if name == 'std_msgs/msg/Header' and value == 'auto' and stamps.header_auto:
        header = type(current)()
        stamps.setters.append(lambda now: setattr(header, 'stamp', now))
        return header
    if name == 'builtin_interfaces/msg/Time' and value == 'now' and stamps.time_now:
        stamp = type(current)()

        def refresh(now: Any) -> None:
            stamp.sec, stamp.nanosec = now.sec, now.nanosec
        stamps.setters.append(refresh)
        return stamp
    return None


def _fill(message: Any, values: Any, path: str, stamps: _Stamps | None) -> Any:
    type_name = type_name_of(type(message))
    if not isinstance(values, dict):
        where = f"field '{path}'" if path else 'the values'
        raise FieldError(f'{where} must be a mapping of {type_name} fields, got {_describe(values)}')
    fields = dict(fields_of(message))
    for key, value in values.items():
        name = str(key)
        field_path = f'{path}.{name}' if path else name
        if name not in fields:
            known = ', '.join(fields) or 'no fields'
            raise FieldError(f"unknown field '{field_path}'{did_you_mean(name, fields)}; "
                             f'{type_name} has: {known}')
        converted = _convert(value, fields[name], getattr(message, name), field_path, stamps)
        try:
            setattr(message, name, converted)
        except (AssertionError, TypeError, ValueError) as error:
            raise FieldError(f"field '{field_path}': {error}") from None
    return message


def set_message_fields(msg: Any, values: Any, expand_header_auto: bool = False,
                       expand_time_now: bool = False) -> list[StampSetter]:
    """Set the message's fields from a mapping (e.g. parsed YAML), recursively; None sets nothing.

    A misfit raises FieldError (a ValueError) with one line naming the field.

    With expand_header_auto, `header: auto` (a std_msgs/Header) is accepted, and with
    expand_time_now, `stamp: now` (a builtin_interfaces/Time); for each such field a setter is
    returned, to be called with the current time (a builtin_interfaces/Time) before each use.
    """
    stamps = _Stamps(expand_header_auto, expand_time_now) if expand_header_auto or expand_time_now else None
    _fill(msg, {} if values is None else values, '', stamps)
    return stamps.setters if stamps else []
