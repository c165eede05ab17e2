"""Upstream rosidl_runtime_py.import_message: the Python class of a rosidl_parser NamespacedType."""

import importlib
from typing import Any


def import_message_from_namespaced_type(message_type: Any) -> Any:
    """The class that a NamespacedType (('pkg', 'msg'), 'Name') names."""
    module = importlib.import_module('.'.join(message_type.value_type.namespaces
                                              if hasattr(message_type, 'value_type')
                                              else message_type.namespaces))
    name = message_type.value_type.name if hasattr(message_type, 'value_type') else message_type.name
    return getattr(module, name)
