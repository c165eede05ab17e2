"""The one message codec of `ros2`: messages <-> YAML / plain data / CSV, as upstream formats them.

Used by `topic echo/pub`, `service call`, `action send_goal`, `interface proto` (and free for
other tools). Output follows rosidl_runtime_py: fields in declaration order, block-style
mappings, PyYAML scalars. Input fills a message from a YAML mapping with one-line errors that
name the field, the expected type and the closest valid field name.
"""

import sys
from collections.abc import Callable
from typing import Any

import yaml
from rosidl_parser.definition import (
    AbstractGenericString,
    AbstractNestedType,
    AbstractWString,
    Array,
    BasicType,
    BoundedSequence,
    BoundedString,
    BoundedWString,
    NamespacedType,
)

from ros2cli.names import did_you_mean

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


class _Fields(dict):
    """A message's fields in declaration order (dumped as a block mapping, never sorted)."""


class _Dumper(yaml.SafeDumper):
    pass


def _represent_fields(dumper: yaml.SafeDumper, data: _Fields) -> yaml.Node:
    items = [(dumper.represent_data(k), dumper.represent_data(v)) for k, v in data.items()]
    # flow_style None: a mapping stays in block style even with --flow-style (as upstream).
    return yaml.MappingNode('tag:yaml.org,2002:map', items)


_Dumper.add_representer(_Fields, _represent_fields)


def is_message(value: Any) -> bool:
    return hasattr(value, 'get_fields_and_field_types') and hasattr(value, 'SLOT_TYPES')


def fields_of(message: Any) -> list[tuple[str, Any]]:
    """(field name, rosidl slot type) in declaration order."""
    return list(zip(message.get_fields_and_field_types(), message.SLOT_TYPES, strict=True))


def type_text(slot_type: Any) -> str:
    """The rosidl name of a slot type as upstream's placeholders show it."""
    if isinstance(slot_type, AbstractNestedType):
        slot_type = slot_type.value_type
    if isinstance(slot_type, BasicType):
        return slot_type.typename
    if isinstance(slot_type, AbstractWString):
        return 'wstring'
    if isinstance(slot_type, AbstractGenericString):
        return 'string'
    if isinstance(slot_type, NamespacedType):
        return '/'.join([*slot_type.namespaces, slot_type.name])
    return str(slot_type)


def _array_placeholder(slot_type: Any, length: int) -> str:
    element = type_text(slot_type)
    if isinstance(slot_type, Array):
        return f'<array type: {element}[{slot_type.size}]>'
    if isinstance(slot_type, BoundedSequence):
        return f'<sequence type: {element}[{slot_type.maximum_size}], length: {length}>'
    return f'<sequence type: {element}, length: {length}>'


def _plain_value(value: Any, slot_type: Any, truncate_length: int | None, no_arr: bool,
                 no_str: bool) -> Any:
    if isinstance(slot_type, AbstractNestedType):
        if no_arr:
            return _array_placeholder(slot_type, len(value))
        items = value.tolist() if hasattr(value, 'tolist') else list(value)
        shown = [_plain_value(item, slot_type.value_type, truncate_length, no_arr, no_str)
                 for item in items[:truncate_length]]
        return [*shown, '...'] if truncate_length is not None and len(items) > truncate_length else shown
    if is_message(value):
        return message_to_plain(value, truncate_length, no_arr, no_str)
    if isinstance(value, bytes):
        text = ''.join(chr(byte) for byte in value)
        return text if truncate_length is None or len(text) <= truncate_length else \
            text[:truncate_length] + '...'
    if isinstance(value, str):
        if no_str:
            return f'<string length: <{len(value)}>>'
        if truncate_length is not None and len(value) > truncate_length:
            return value[:truncate_length] + '...'
        return value
    if hasattr(value, 'item'):  # a numpy scalar
        return value.item()
    return value


def message_to_plain(message: Any, truncate_length: int | None = None, no_arr: bool = False,
                     no_str: bool = False) -> dict[str, Any]:
    """The message as nested dicts/lists/scalars in field declaration order."""
    return _Fields(
        (name, _plain_value(getattr(message, name), slot_type, truncate_length, no_arr, no_str))
        for name, slot_type in fields_of(message))


def dump_yaml(data: Any, flow_style: bool = False) -> str:
    """YAML text as upstream prints messages (ends with a newline)."""
    return yaml.dump(data, Dumper=_Dumper, allow_unicode=True, width=sys.maxsize,
                     default_flow_style=flow_style)


def message_to_yaml(message: Any, truncate_length: int | None = None, no_arr: bool = False,
                    no_str: bool = False, flow_style: bool = False) -> str:
    return dump_yaml(message_to_plain(message, truncate_length, no_arr, no_str), flow_style)


def _csv_values(value: Any, slot_type: Any, truncate_length: int | None, no_arr: bool,
                no_str: bool) -> list[str]:
    if isinstance(slot_type, AbstractNestedType):
        if no_arr:
            return [_array_placeholder(slot_type, len(value))]
        items = value.tolist() if hasattr(value, 'tolist') else list(value)
        values: list[str] = []
        for item in items[:truncate_length]:
            values += _csv_values(item, slot_type.value_type, truncate_length, no_arr, no_str)
        return [*values, '...'] if truncate_length is not None and len(items) > truncate_length else values
    if is_message(value):
        return message_to_csv(value, truncate_length, no_arr, no_str).split(',') \
            if fields_of(value) else []
    if isinstance(value, str):
        if no_str:
            return [f'<string length: <{len(value)}>>']
        if truncate_length is not None and len(value) > truncate_length:
            return [value[:truncate_length] + '...']
    return [str(value)]


def message_to_csv(message: Any, truncate_length: int | None = None, no_arr: bool = False,
                   no_str: bool = False) -> str:
    """Every leaf value in declaration order, comma separated (upstream's `echo --csv`)."""
    values: list[str] = []
    for name, slot_type in fields_of(message):
        values += _csv_values(getattr(message, name), slot_type, truncate_length, no_arr, no_str)
    return ','.join(values)


# ---- input: YAML text -> message -------------------------------------------------------------

def parse_yaml(text: str) -> Any:
    """yaml.safe_load with a one-line FieldError for malformed text."""
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as error:
        mark = getattr(error, 'problem_mark', None)
        where = f' (line {mark.line + 1}, column {mark.column + 1})' if mark else ''
        problem = getattr(error, 'problem', None) or str(error).splitlines()[0]
        raise FieldError(f'invalid YAML{where}: {problem}: {text!r}') from None


def _type_name(message_class: Any) -> str:
    package, kind = message_class.__module__.split('.')[:2]
    return f'{package}/{kind}/{message_class.__name__}'


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


def _convert(value: Any, slot_type: Any, current: Any, path: str,
             stamps: list[StampSetter] | None) -> Any:
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
            import importlib
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


def _stamp_keyword(value: str, slot_type: Any, current: Any, path: str,
                   stamps: list[StampSetter]) -> Any:
    """`header: auto` / `stamp: now` (topic pub): the time is written before every publish."""
    name = '/'.join([*slot_type.namespaces, slot_type.name])
    if name == 'std_msgs/msg/Header' and value == 'auto':
        header = type(current)()
        stamps.append(lambda now: setattr(header, 'stamp', now))
        return header
    if name == 'builtin_interfaces/msg/Time' and value == 'now':
        stamp = type(current)()

        def refresh(now: Any) -> None:
            stamp.sec, stamp.nanosec = now.sec, now.nanosec
        stamps.append(refresh)
        return stamp
    return None


def _fill(message: Any, values: Any, path: str, stamps: list[StampSetter] | None) -> Any:
    type_name = _type_name(type(message))
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


def fill_message(message: Any, values: Any, stamps: list[StampSetter] | None = None) -> Any:
    """Set the message's fields from a mapping (e.g. parsed YAML); FieldError on a misfit.

    With a `stamps` list, `header: auto` and `stamp: now` are accepted and a setter per such
    field is appended to it.
    """
    return _fill(message, {} if values is None else values, '', stamps)
