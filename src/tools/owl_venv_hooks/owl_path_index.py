"""The venv's top-level imports look only in the folders of sys.path that hold the name.

A shell of this workspace has about 70 entries on sys.path: colcon's isolated install puts each
package's site-packages (and, for --symlink-install, its build folder) on PYTHONPATH, ahead of
Python's own library and the venv. Python's path finder asks every entry in turn for every
top-level import, so each `import ssl` or `import numpy` first looks in some 70 folders that do not
have it: about a quarter of a ROS node's start-up CPU (0.08 s of `import numpy`'s 0.19 s, 0.08 s of
`import aiohttp`'s 0.36 s), paid by every node, every `ros2` command and every launch.

install() puts a path finder in place of Python's that lists each folder of sys.path once and, for
a top-level import, hands Python's own search only the entries whose listing has an entry of that
name (a module, a package, a namespace portion, anything that could be one) and every entry it
did not list (the current folder, a zip, one added later and not yet listed). A folder without the
name cannot give a module or a portion of it, so the result is the one Python's search over all of
sys.path gives, found with a few lookups instead of 70 folder checks. importlib.invalidate_caches()
lists the folders again, as it refreshes Python's own finders, and so does an import that finds
nothing when a listed folder changed since (a module written after the start, which Python's own
finders notice by the folder's time too); submodules are searched in their package's __path__ as
before.

scripts/bootstrap.sh copies this module into the venv's site-packages with a .pth line that calls
install() at every start of the venv's Python.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Sequence
from importlib.machinery import ModuleSpec, PathFinder
from types import ModuleType

# folder (as written on sys.path) -> (its modification time, the names its entries could be imported as)
_listings: dict[str, tuple[int, frozenset[str]]] = {}


def _list(folder: str) -> tuple[int, frozenset[str]] | None:
    try:
        modified = os.stat(folder).st_mtime_ns
        entries = os.listdir(folder)
    except OSError:
        return None  # not a folder (a zip) or not there yet: Python's search decides
    return modified, frozenset(entry.partition('.')[0] for entry in entries)


def _names_in(folder: str) -> frozenset[str] | None:
    """What the folder's entries could be imported as (each name up to its first dot); None: not listed."""
    listed = _listings.get(folder)
    if listed is None:
        if not folder or not os.path.isabs(folder):
            return None  # relative to the current folder, which may change
        listed = _list(folder)
        if listed is None:
            return None
        _listings[folder] = listed
    return listed[1]


def _relist_changed() -> bool:
    """List again the folders changed since they were listed; whether any was."""
    changed = False
    for folder, (modified, _) in list(_listings.items()):
        try:
            if os.stat(folder).st_mtime_ns == modified:
                continue
        except OSError:
            pass
        del _listings[folder]
        changed = True
    return changed


class IndexedPathFinder(PathFinder):
    """Python's path finder, asking only the folders of sys.path that could hold a top-level name."""

    @classmethod
    def find_spec(cls, fullname: str, path: Sequence[str] | None = None,
                  target: ModuleType | None = None) -> ModuleSpec | None:
        """PathFinder.find_spec, a top-level name searched in the entries of sys.path that may hold it."""
        if path is not None:  # a submodule: its package's folders
            return super().find_spec(fullname, path, target)
        spec = super().find_spec(fullname, cls._candidates(fullname), target)
        if spec is None and _relist_changed():  # a module made since its folder was listed
            spec = super().find_spec(fullname, cls._candidates(fullname), target)
        return spec

    @staticmethod
    def _candidates(name: str) -> list[str]:
        return [entry for entry in sys.path if (names := _names_in(entry)) is None or name in names]

    @classmethod
    def invalidate_caches(cls) -> None:
        """Forget every listing, and Python's own finders' caches."""
        _listings.clear()
        super().invalidate_caches()


def install() -> None:
    """Put IndexedPathFinder where Python's path finder is on sys.meta_path (once)."""
    for index, finder in enumerate(sys.meta_path):
        if finder is PathFinder:
            sys.meta_path[index] = IndexedPathFinder
            return
