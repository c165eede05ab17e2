"""Installed interfaces, from the ament index: upstream rosidl_runtime_py.get_interfaces."""

import os
from functools import cache

KINDS = ('msg', 'srv', 'action')  # the interface kinds an ament index entry can name


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


def get_interface_packages() -> dict[str, str]:
    """{package: its prefix} of every package that provides interfaces."""
    from ament_index_python.packages import get_package_prefix
    return {package: get_package_prefix(package) for package in sorted(interface_index())}


def _interfaces(kinds: tuple[str, ...], package_names: list[str] | None) -> dict[str, list[str]]:
    index = interface_index()
    if package_names is not None:
        missing = [name for name in package_names if name not in index]
        if missing:
            raise LookupError(f"Unknown package '{missing[0]}'")
    return {package: [f'{kind}/{name}' for kind in kinds for name in index[package][kind]]
            for package in (package_names if package_names is not None else sorted(index))}


def get_interfaces(package_names: list[str] | None = None) -> dict[str, list[str]]:
    """{package: ['msg/Name', 'srv/Name', 'action/Name', ...]}; LookupError for an unknown package."""
    return _interfaces(KINDS, package_names)


def get_message_interfaces(package_names: list[str] | None = None) -> dict[str, list[str]]:
    """{package: ['msg/Name', ...]}: the messages only, as get_interfaces lists them."""
    return _interfaces(('msg',), package_names)


def get_service_interfaces(package_names: list[str] | None = None) -> dict[str, list[str]]:
    """{package: ['srv/Name', ...]}: the services only, as get_interfaces lists them."""
    return _interfaces(('srv',), package_names)


def get_action_interfaces(package_names: list[str] | None = None) -> dict[str, list[str]]:
    """{package: ['action/Name', ...]}: the actions only, as get_interfaces lists them."""
    return _interfaces(('action',), package_names)


def get_interface_path(interface_name: str) -> str:
    """The installed definition file of an interface; LookupError when there is none.

    For 'pkg/msg/Name' that is its .msg/.srv/.action, else its .idl; a name with its extension
    ('pkg/msg/Name.idl') gives that file.  ValueError for a name of another shape.
    """
    from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
    parts = interface_name.split('/')
    if len(parts) != 3 or not all(parts):
        raise ValueError(f"'{interface_name}' is not '<package>/<msg|srv|action>/<Name>'")
    package, kind, name = parts
    try:
        share = get_package_share_directory(package)
    except PackageNotFoundError:
        raise LookupError(f"Unknown package '{package}'") from None
    extension = os.path.splitext(name)[1]
    candidates = [name] if extension else [f'{name}.{kind}', f'{name}.idl']
    for candidate in candidates:
        path = os.path.join(share, kind, candidate)
        if os.path.isfile(path):
            return path
    raise LookupError(f"Could not find the interface '{interface_name}'")
