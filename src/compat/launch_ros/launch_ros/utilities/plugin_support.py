"""Version checks for plugins (Node's `launch_ros.node_action` extensions): caret ranges like '^0.1'."""

from __future__ import annotations

from packaging.version import Version

__all__ = ['PluginException', 'get_upper_bound_caret_version', 'satisfies_version']


class PluginException(Exception):
    """A plugin cannot be used, e.g. because it was written for another version of the extension point."""


def get_upper_bound_caret_version(version: Version) -> Version:
    """The first version a caret range starting at `version` excludes.

    That is the next major version, or the next minor one while the major is 0 ('^0.1' allows 0.1.x,
    not 0.2).
    """
    major, minor = ([*version.release, 0][:2])
    if major > 0:
        return Version(f'{major + 1}.0.0')
    return Version(f'0.{minor + 1}.0')


def satisfies_version(version: str, caret_range: str) -> None:
    """Check that `version` (the extension point's) is within `caret_range` (what the plugin wants).

    PluginException if it is not; ValueError for a range that is not a caret one.
    """
    if not caret_range.startswith('^'):
        raise ValueError(f"only caret ranges ('^1.2') are supported, got '{caret_range}'")
    available = Version(version)
    lowest = Version(caret_range[1:])
    if available < lowest:
        raise PluginException(f"Extension point is too old ({available}), the extension requires '{lowest}'")
    if available >= get_upper_bound_caret_version(lowest):
        raise PluginException(f'Extension point is newer ({available}) than what the extension '
                              f"supports '{lowest}'")
