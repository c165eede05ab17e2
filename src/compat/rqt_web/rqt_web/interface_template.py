"""The forms of Message Publisher and Service Caller: a message type's fields with defaults (node-free)."""

import math
from typing import Any

from ros2cli.message_yaml import fields_of, is_message, message_to_plain
from rosidl_parser.definition import AbstractNestedType, NamespacedType


def field_template(message: Any) -> list[dict[str, Any]]:
    """[{name, type, default} or {name, type, fields: [...]}, ...] in declaration order.

    A nested message (not in a sequence) gets its own fields; everything else, sequences and
    arrays included, is one cell whose default is the value of a fresh message.
    """
    template = []
    defaults = message_to_plain(message)
    for (name, type_text), (_, slot_type) in zip(message.get_fields_and_field_types().items(),
                                                 fields_of(message), strict=True):
        value = getattr(message, name)
        entry: dict[str, Any] = {'name': name, 'type': type_text}
        if isinstance(slot_type, NamespacedType) and is_message(value):
            entry['fields'] = field_template(value)
        else:
            entry['default'] = json_safe(defaults[name])
            if isinstance(slot_type, AbstractNestedType):
                entry['sequence'] = True
        template.append(entry)
    return template


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
    """A message's values as JSON-safe nested dicts/lists in declaration order."""
    return json_safe(message_to_plain(message))
