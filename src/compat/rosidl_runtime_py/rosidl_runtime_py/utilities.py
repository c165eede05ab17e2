"""Interface types by name: upstream rosidl_runtime_py.utilities.

get_message, get_service, get_action, get_interface, get_namespaced_type and
is_message/is_service/is_action, on a lookup that says in one line why a name is wrong, with the
closest installed name.
"""

import importlib
from typing import Any

from owl_common.hints import did_you_mean

from rosidl_runtime_py.get_interfaces import KINDS, interface_index

KIND_WORDS = {'msg': 'message', 'srv': 'service', 'action': 'action'}


class InvalidType(ValueError):
    """A type name that names no installed interface of the wanted kind; str() says why.

    A ValueError, as upstream's lookups raise.
    """


def split_type(type_name: str, kind: str) -> tuple[str, str, str]:
    """'pkg/Name' or 'pkg/<kind>/Name' as (pkg, kind, Name); InvalidType for other shapes."""
    parts = type_name.split('/')
    if len(parts) == 2 and all(parts):
        return parts[0], kind, parts[1]
    if len(parts) == 3 and all(parts) and parts[1] == kind:
        return parts[0], kind, parts[2]
    raise InvalidType(f"'{type_name}' is not a {KIND_WORDS[kind]} type name; expected "
                      f"'<package>/{kind}/<Name>' or '<package>/<Name>'")


def canonical_type(type_name: str, kind: str) -> str:
    """'pkg/kind/Name' for 'pkg/Name' or 'pkg/kind/Name'; InvalidType for other shapes."""
    package, kind, name = split_type(type_name, kind)
    return f'{package}/{kind}/{name}'


def why_not_found(package: str, kind: str, name: str) -> str:
    """A one-line reason why package/kind/name is not installed, with the closest names."""
    index = interface_index()
    if package not in index:
        return f"unknown package '{package}'{did_you_mean(package, index)}"
    names = index[package][kind]
    if name not in names:
        hint = did_you_mean(name, names)
        if not hint:
            others = [f'{package}/{k}/{n}' for k in KINDS for n in index[package][k] if n == name]
            hint = f" (it is '{others[0]}')" if others else ''
        return f"package '{package}' has no {KIND_WORDS[kind]} '{name}'{hint}"
    return f"'{package}/{kind}/{name}' could not be imported"


def import_type(type_name: str, kind: str) -> Any:
    """The generated Python class of a type name; InvalidType (with a reason) when there is none."""
    package, kind, name = split_type(type_name, kind)
    try:
        module = importlib.import_module(f'{package}.{kind}')
        type_class = getattr(module, name)
    except (ImportError, AttributeError, ValueError):
        raise InvalidType(why_not_found(package, kind, name)) from None
    if not {'msg': is_message, 'srv': is_service, 'action': is_action}[kind](type_class):
        raise InvalidType(f"'{type_name}' is not a {KIND_WORDS[kind]} type")
    return type_class


def type_name_of(type_class: Any) -> str:
    """'geometry_msgs/msg/Twist' for the class geometry_msgs.msg.Twist."""
    package, kind = type_class.__module__.split('.')[:2]
    return f'{package}/{kind}/{type_class.__name__}'


def is_message(msg_or_type: Any) -> bool:
    """A generated message class or instance (has its field table)."""
    return hasattr(msg_or_type, 'get_fields_and_field_types') and hasattr(msg_or_type, 'SLOT_TYPES')


def is_service(srv_or_type: Any) -> bool:
    """A generated service class or instance: its Request and Response are messages."""
    return is_message(getattr(srv_or_type, 'Request', None)) and \
        is_message(getattr(srv_or_type, 'Response', None))


def is_action(action_or_type: Any) -> bool:
    """A generated action class or instance: its Goal, Result and Feedback are messages."""
    return all(is_message(getattr(action_or_type, part, None)) for part in ('Goal', 'Result', 'Feedback'))


def get_namespaced_type(identifier: str) -> Any:
    """'pkg/msg/Name' as a rosidl_parser NamespacedType (('pkg', 'msg'), 'Name')."""
    from rosidl_parser.definition import NamespacedType
    *namespaces, name = identifier.split('/')
    if len(namespaces) != 2 or not all(namespaces) or not name:
        raise InvalidType(f"'{identifier}' is not a type name; expected '<package>/<kind>/<Name>'")
    return NamespacedType(namespaces, name)


def get_message(identifier: str) -> Any:
    """The message class of 'pkg/msg/Name' (or 'pkg/Name'); InvalidType (a ValueError) if none."""
    return import_type(identifier, 'msg')


def get_service(identifier: str) -> Any:
    """The service class of 'pkg/srv/Name' (or 'pkg/Name'); InvalidType (a ValueError) if none."""
    return import_type(identifier, 'srv')


def get_action(identifier: str) -> Any:
    """The action class of 'pkg/action/Name' (or 'pkg/Name'); InvalidType (a ValueError) if none."""
    return import_type(identifier, 'action')


def get_interface(identifier: str) -> Any:
    """The class of 'pkg/<msg|srv|action>/Name', whichever kind the name says."""
    parts = identifier.split('/')
    if len(parts) != 3 or parts[1] not in KINDS:
        raise InvalidType(f"'{identifier}' is not an interface type name; expected "
                          "'<package>/<msg|srv|action>/<Name>'")
    return import_type(identifier, parts[1])
