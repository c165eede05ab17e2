"""Message definitions as MCAP's `ros2msg` schemas: the type's fields, then each nested type's.

A schema holds the whole definition a reader needs to decode without ROS: the top type's field
lines, then, for every type it uses, a line of 80 '=', `MSG: <package>/<Type>` and that type's
field lines. They are built from the generated Python classes (what rclpy itself serializes),
so message, service request/response and service event types all work alike. Comments and
constants of the .msg files are not kept (no reader needs them to decode).
"""

from __future__ import annotations

import importlib
from typing import Any

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

SEPARATOR = '=' * 80
# The IDL names of basic types, as .msg files spell them.
MSG_NAMES = {'boolean': 'bool', 'octet': 'byte', 'float': 'float32', 'double': 'float64',
             'long double': 'float64'}


def _namespaced_name(slot: NamespacedType) -> str:
    return f'{next(iter(slot.namespaces))}/{slot.name}'


def _element_text(slot: Any) -> str:
    if isinstance(slot, BasicType):
        return MSG_NAMES.get(slot.typename, slot.typename)
    if isinstance(slot, BoundedWString):
        return f'wstring<={slot.maximum_size}'
    if isinstance(slot, AbstractWString):
        return 'wstring'
    if isinstance(slot, BoundedString):
        return f'string<={slot.maximum_size}'
    if isinstance(slot, AbstractGenericString):
        return 'string'
    if isinstance(slot, NamespacedType):
        return _namespaced_name(slot)
    raise ValueError(f'unknown field type {slot!r}')


def field_type_text(slot: Any) -> str:
    """A field's type as a .msg file writes it: 'float64', 'std_msgs/Header', 'uint8[]', 'int32[<=1]'."""
    if isinstance(slot, Array):
        return f'{_element_text(slot.value_type)}[{slot.size}]'
    if isinstance(slot, BoundedSequence):
        return f'{_element_text(slot.value_type)}[<={slot.maximum_size}]'
    if isinstance(slot, AbstractNestedType):
        return f'{_element_text(slot.value_type)}[]'
    return _element_text(slot)


def type_class(slot: NamespacedType) -> Any:
    """The generated class of a nested type, including a service's _Request/_Response/_Event."""
    module = importlib.import_module('.'.join(slot.namespaces))
    if hasattr(module, slot.name):
        return getattr(module, slot.name)
    base, _, part = slot.name.rpartition('_')
    return getattr(getattr(module, base), part)


def _fields(cls: Any) -> list[tuple[str, Any]]:
    return list(zip(cls.get_fields_and_field_types(), cls.SLOT_TYPES, strict=True))


def message_definition(cls: Any) -> str:
    """The `ros2msg` schema text of a generated message class."""
    sections = ['\n'.join(f'{field_type_text(slot)} {name}' for name, slot in _fields(cls))]
    seen: set[str] = set()
    pending = [cls]
    while pending:
        for _, slot in _fields(pending.pop(0)):
            nested = slot.value_type if isinstance(slot, AbstractNestedType) else slot
            if not isinstance(nested, NamespacedType) or _namespaced_name(nested) in seen:
                continue
            seen.add(_namespaced_name(nested))
            nested_class = type_class(nested)
            body = '\n'.join(f'{field_type_text(s)} {n}' for n, s in _fields(nested_class))
            sections.append(f'{SEPARATOR}\nMSG: {_namespaced_name(nested)}\n{body}')
            pending.append(nested_class)
    return '\n'.join(sections) + '\n'
