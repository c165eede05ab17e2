"""Owl Kit Lab's one message library, under upstream rosidl_runtime_py's names.

The pinned Jazzy wheels do not ship rosidl_runtime_py; this package stands in for it, so that code
written against upstream runs:

- convert: message_to_yaml, message_to_ordereddict, message_to_csv
- set_message: set_message_fields (one-line FieldError on a misfit)
- utilities: get_message, get_service, get_action, get_interface, get_namespaced_type,
  is_message, is_service, is_action
- get_interfaces: get_interface_packages, get_interfaces, get_message_interfaces,
  get_service_interfaces, get_action_interfaces, get_interface_path
- import_message: import_message_from_namespaced_type

The type lookup in utilities gives its reasons (and the closest installed type) in its errors; the
graph queries and name hints that ros2cli and the web tools share live in owl_common.
"""

from rosidl_runtime_py.convert import message_to_csv, message_to_ordereddict, message_to_yaml
from rosidl_runtime_py.get_interfaces import (
    get_action_interfaces,
    get_interface_packages,
    get_interface_path,
    get_interfaces,
    get_message_interfaces,
    get_service_interfaces,
)
from rosidl_runtime_py.import_message import import_message_from_namespaced_type
from rosidl_runtime_py.set_message import set_message_fields

__all__ = [
    'get_action_interfaces', 'get_interface_packages', 'get_interface_path', 'get_interfaces',
    'get_message_interfaces', 'get_service_interfaces', 'import_message_from_namespaced_type',
    'message_to_csv', 'message_to_ordereddict', 'message_to_yaml', 'set_message_fields',
]
