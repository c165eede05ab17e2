"""Versions and instances of extensions, under upstream ros2cli's names.

The names are kept so that extensions written for upstream
(`satisfies_version(PLUGIN_SYSTEM_VERSION, '^0.1')` in their __init__) load here.
"""

from __future__ import annotations

from typing import Any

from ros2cli.entry_points import get_entry_points, load_entry_point, warn

PLUGIN_SYSTEM_VERSION = '0.1'


class PluginException(Exception):
    """An extension that does not fit the extension point; str() says why."""


def _numbers(version: str) -> list[int]:
    try:
        return [int(part) for part in version.split('.')]
    except ValueError:
        raise PluginException(f"'{version}' is not a version of dot-separated numbers") from None


def satisfies_version(version: str, caret_range: str) -> None:
    """PluginException unless `version` lies in the caret range.

    The range follows npm's rule: '^0.1' is >=0.1 <0.2, '^1.2' is >=1.2 <2.0 (below 1.0 the minor
    number breaks compatibility).
    """
    if not caret_range.startswith('^'):
        raise PluginException(f"'{caret_range}' is not a caret range such as '^0.1'")
    have, want = _numbers(version), _numbers(caret_range[1:])
    significant = next((i for i, number in enumerate(want) if number), len(want) - 1)
    padded = have + [0] * (len(want) - len(have))
    if padded[:len(want)] < want or padded[:significant + 1] != want[:significant + 1]:
        raise PluginException(f'extension point version {version} does not satisfy {caret_range}')


def instantiate_extension(group_name: str, name: str, extension_class: Any) -> Any | None:
    """An instance of the class, or None (with one warning line) when its construction fails."""
    try:
        return extension_class()
    except Exception as error:  # PluginException or a third party's bug: warn, keep the rest
        warn(f"skipped '{name}' of '{group_name}': {type(error).__name__}: {' '.join(str(error).split())}")
        return None


def instantiate_extensions(group_name: str, *, exclude_names: list[str] | None = None,
                           names: list[str] | None = None) -> dict[str, Any]:
    """{name: instance} of the group's extensions (only `names`, if given), broken ones left out."""
    instances = {}
    for name, entry_point in sorted(get_entry_points(group_name).items()):
        if name in (exclude_names or ()) or (names is not None and name not in names):
            continue
        extension_class = load_entry_point(entry_point)
        if extension_class is None:
            continue
        instance = instantiate_extension(group_name, name, extension_class)
        if instance is not None:
            instances[name] = instance
    return instances
