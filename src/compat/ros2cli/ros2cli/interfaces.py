"""Interface types: the installed .msg/.srv/.action files (ament index) and their Python classes."""

import importlib
from functools import cache
from typing import Any

from ros2cli.names import did_you_mean

KINDS = ('msg', 'srv', 'action')
KIND_WORDS = {'msg': 'message', 'srv': 'service', 'action': 'action'}


class InvalidType(Exception):
    """A type name that names no installed interface of the wanted kind; str() says why."""


@cache
def interface_index() -> dict[str, dict[str, list[str]]]:
    """{package: {'msg': [Name, ...], 'srv': [...], 'action': [...]}} of every installed package."""
    from ament_index_python.resources import get_resource, get_resources

    index: dict[str, dict[str, list[str]]] = {}
    for package in get_resources('rosidl_interfaces'):
        content, _ = get_resource('rosidl_interfaces', package)
        kinds: dict[str, set[str]] = {kind: set() for kind in KINDS}
        for line in content.splitlines():
            kind, _, file_name = line.strip().partition('/')
            stem, _, extension = file_name.rpartition('.')
            if kind in kinds and extension in ('idl', kind):
                kinds[kind].add(stem)
        index[package] = {kind: sorted(names) for kind, names in kinds.items()}
    return index


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
    wanted = {'msg': 'get_fields_and_field_types', 'srv': 'Request', 'action': 'Goal'}[kind]
    if not hasattr(type_class, wanted):
        raise InvalidType(f"'{type_name}' is not a {KIND_WORDS[kind]} type")
    return type_class


def type_name_of(type_class: Any) -> str:
    """'geometry_msgs/msg/Twist' for the class geometry_msgs.msg.Twist."""
    package, kind = type_class.__module__.split('.')[:2]
    return f'{package}/{kind}/{type_class.__name__}'
