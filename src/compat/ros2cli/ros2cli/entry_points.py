"""The entry points through which `ros2` finds its commands and verbs, as upstream ros2cli does.

A package plugs a command into `ros2` by declaring, in its setup.py,
    entry_points={'ros2cli.command': ['hello = ros2hello.command:HelloCommand'],
                  'ros2hello.verb': ['world = ros2hello.verb:WorldVerb']}
and nothing in ros2cli names it. Groups: 'ros2cli.command' for commands, '<command package>.verb'
(e.g. 'ros2topic.verb') for each command's verbs, 'ros2cli.extension_point' for the extension
points themselves.

Speed: importlib.metadata.entry_points(group=...) reads every installed distribution's metadata
on each call, to de-duplicate by name (about 11 ms per call for the ~230 distributions of a sourced
workspace on a 2-core machine, 25 ms and more under load), and `ros2 topic list` needs two groups;
importing importlib.metadata alone (email, zipfile, csv) took 15-20 ms of every `ros2` call. Only
the entry_points.txt files matter here, so they are read once per process for all groups: those of
the *.dist-info and *.egg-info folders of each sys.path entry, in sys.path order, which is where
importlib.metadata finds them too (about 4 ms); a name declared twice keeps its first declaration,
as sys.path order says. bench/ros2_help.py times `ros2 -h` end to end.
"""

from __future__ import annotations

import importlib
import os
import sys
from functools import reduce
from typing import Any, NamedTuple

METADATA_FOLDERS = ('.dist-info', '.egg-info')


class EntryPoint(NamedTuple):
    """One `name = module:attr` line of an entry_points.txt, as importlib.metadata's EntryPoint has it."""

    name: str
    value: str  # 'module:attr.path', optionally followed by '[extras]' (ignored, as upstream does)
    group: str

    def load(self) -> Any:
        """Import the module and return the attribute the value names (the module itself without one)."""
        module, _, attributes = self.value.partition('[')[0].partition(':')
        return reduce(getattr, filter(None, attributes.strip().split('.')),
                      importlib.import_module(module.strip()))


_BY_GROUP: dict[str, dict[str, EntryPoint]] | None = None


def _parse(text: str, into: dict[str, dict[str, EntryPoint]]) -> None:
    """The sections of an entry_points.txt (INI: `[group]`, then `name = module:attr` lines)."""
    group = None
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line[0] in '#;':
            continue
        if line.startswith('[') and line.endswith(']'):
            group = line[1:-1].strip()
            continue
        name, equals, value = line.partition('=')
        if group is None or not equals:
            continue  # not an entry point line; importlib.metadata would skip it too
        name = name.strip()
        into.setdefault(group, {}).setdefault(name, EntryPoint(name=name, value=value.strip(), group=group))


def _entry_points_files() -> list[str]:
    """The entry_points.txt paths of every distribution on sys.path, in sys.path order (some absent)."""
    files = []
    for entry in sys.path:
        folder = entry or '.'
        try:
            names = os.listdir(folder)  # in the order importlib.metadata takes them too
        except OSError:  # a zip file or a folder that is not there: no entry points of ours
            continue
        files += [os.path.join(folder, name, 'entry_points.txt') for name in names
                  if name.endswith(METADATA_FOLDERS)]
    return files


def _all_entry_points() -> dict[str, dict[str, EntryPoint]]:
    global _BY_GROUP
    if _BY_GROUP is None:
        found: dict[str, dict[str, EntryPoint]] = {}
        for path in _entry_points_files():
            try:
                with open(path, encoding='utf-8') as file:
                    text = file.read()
            except (OSError, UnicodeDecodeError):  # no entry points, or an unreadable file: skipped
                continue
            _parse(text, found)
        _BY_GROUP = found
    return _BY_GROUP


def get_entry_points(group_name: str) -> dict[str, EntryPoint]:
    """{name: entry point} of one group, without importing anything."""
    return dict(_all_entry_points().get(group_name, {}))


def get_entry_point_groups() -> list[str]:
    """The names of every entry point group of the installed distributions, sorted."""
    return sorted(_all_entry_points())


def warn(message: str) -> None:
    """One line on stderr: a broken extension is reported, and everything else still works."""
    print(f'ros2: warning: {message}', file=sys.stderr)


def load_entry_point(entry_point: EntryPoint) -> Any | None:
    """What the entry point names, or None (with one warning line) when it cannot be imported."""
    try:
        return entry_point.load()
    except Exception as error:  # a third party's import error must not break `ros2`
        detail = ' '.join(str(error).split())
        warn(f"skipped '{entry_point.name}' of '{entry_point.group}' ({entry_point.value}): "
             f'{type(error).__name__}: {detail}')
        return None


def load_entry_points(group_name: str, names: list[str] | None = None) -> dict[str, Any]:
    """{name: loaded object} of a group (or only of `names`); broken ones are warned about and left out."""
    loaded = {}
    for name, entry_point in sorted(get_entry_points(group_name).items()):
        if names is not None and name not in names:
            continue
        target = load_entry_point(entry_point)
        if target is not None:
            loaded[name] = target
    return loaded


def get_first_line_doc(any_type: Any) -> str:
    """The first non-blank line of a docstring without its closing period: what `-h` lists."""
    for line in (getattr(any_type, '__doc__', None) or '').splitlines():
        if line.strip():
            return line.strip().removesuffix('.')
    return ''
