"""The forms of Message Publisher and Service Caller: a message type's fields with defaults (node-free)."""

from typing import Any, Protocol

from owl_web.codec import json_safe
from rosidl_parser.definition import AbstractNestedType, NamespacedType
from rosidl_runtime_py.convert import fields_of, message_to_ordereddict
from rosidl_runtime_py.utilities import is_message


class RosMessage(Protocol):
    """A generated ROS message (rosidl), as far as the forms and publishers here use it."""

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """{field name: type text} of the message, in declaration order, as rosidl generates it."""


def field_template(message: RosMessage) -> list[dict[str, Any]]:
    """[{name, type, default} or {name, type, fields: [...]}, ...] in declaration order.

    A nested message (not in a sequence) gets its own fields; everything else, sequences and
    arrays included, is one cell whose default is the value of a fresh message.
    """
    template = []
    defaults = message_to_ordereddict(message)
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
