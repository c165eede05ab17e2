"""Messages as YAML, ordered dicts and CSV, as upstream rosidl_runtime_py.convert formats them.

Fields in declaration order, block-style mappings, PyYAML scalars (what `ros2 topic echo` prints).
"""

import sys
from collections import OrderedDict
from typing import Any

import yaml
from rosidl_parser.definition import (
    AbstractGenericString,
    AbstractNestedType,
    AbstractWString,
    Array,
    BasicType,
    BoundedSequence,
    NamespacedType,
)

from rosidl_runtime_py.utilities import is_message


class _Fields(OrderedDict[str, Any]):
    """A message's fields in declaration order (dumped as a block mapping, never sorted)."""


class _Dumper(yaml.SafeDumper):
    pass


def _represent_fields(dumper: yaml.SafeDumper, data: _Fields) -> yaml.Node:
    items = [(dumper.represent_data(k), dumper.represent_data(v)) for k, v in data.items()]
    # flow_style None: a mapping stays in block style even with --flow-style (as upstream).
    return yaml.MappingNode('tag:yaml.org,2002:map', items)


_Dumper.add_representer(_Fields, _represent_fields)


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
        return message_to_ordereddict(value, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str)
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


def message_to_ordereddict(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False,
                           no_str: bool = False) -> OrderedDict[str, Any]:
    """The message as nested OrderedDicts/lists/scalars, in field declaration order.

    Strings and sequences longer than truncate_length are cut ('...'); no_arr/no_str show
    placeholders instead of them.
    """
    message = msg
    return _Fields(
        (name, _plain_value(getattr(message, name), slot_type, truncate_length, no_arr, no_str))
        for name, slot_type in fields_of(message))


def dump_yaml(data: Any, flow_style: bool = False) -> str:
    """YAML text as upstream prints messages (ends with a newline)."""
    return yaml.dump(data, Dumper=_Dumper, allow_unicode=True, width=sys.maxsize,
                     default_flow_style=flow_style)


def message_to_yaml(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False,
                    no_str: bool = False, flow_style: bool = False) -> str:
    """The message as upstream's `ros2 topic echo` prints it (ends with a newline)."""
    return dump_yaml(message_to_ordereddict(msg, truncate_length=truncate_length, no_arr=no_arr,
                                            no_str=no_str), flow_style)


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
        if not fields_of(value):
            return []
        return message_to_csv(value, truncate_length=truncate_length, no_arr=no_arr, no_str=no_str).split(',')
    if isinstance(value, str):
        if no_str:
            return [f'<string length: <{len(value)}>>']
        if truncate_length is not None and len(value) > truncate_length:
            return [value[:truncate_length] + '...']
    return [str(value)]


def message_to_csv(msg: Any, *, truncate_length: int | None = None, no_arr: bool = False,
                   no_str: bool = False) -> str:
    """Every leaf value in declaration order, comma separated (upstream's `echo --csv`)."""
    message = msg
    values: list[str] = []
    for name, slot_type in fields_of(message):
        values += _csv_values(getattr(message, name), slot_type, truncate_length, no_arr, no_str)
    return ','.join(values)


