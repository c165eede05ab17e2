"""The files a linter checks, found the way ament's linters look for them."""

from __future__ import annotations

import fnmatch
import os
from collections.abc import Iterable


class LintInputError(Exception):
    """A request a linter cannot carry out (a missing path, no ruff); str() is one line for the user."""


def is_excluded(path: str, excludes: Iterable[str]) -> bool:
    """Whether an --exclude entry names this file or folder, by path or by a pattern on its name."""
    real = os.path.realpath(path)
    name = os.path.basename(os.path.normpath(path))
    return any(real == os.path.realpath(pattern) or fnmatch.fnmatch(name, pattern) for pattern in excludes)


def find_files(paths: Iterable[str], suffixes: tuple[str, ...], excludes: Iterable[str] = ()) -> list[str]:
    """Files to check under `paths`, each once, in order.

    Inside a folder: files ending in one of `suffixes`, skipping folders whose name starts with '.'
    or '_' and folders that hold an AMENT_IGNORE file, as upstream does. A file named directly is
    checked whatever its name. A path that does not exist raises LintInputError rather than being
    passed over silently.
    """
    excludes = list(excludes)
    found: dict[str, None] = {}
    for path in paths:
        if not os.path.exists(path):
            raise LintInputError(f'{path}: no such file or directory')
        if is_excluded(path, excludes):
            continue
        if not os.path.isdir(path):
            found[os.path.normpath(path)] = None
            continue
        for folder, subfolders, names in os.walk(path):
            if 'AMENT_IGNORE' in names or 'AMENT_IGNORE' in subfolders:
                subfolders[:] = []
                continue
            subfolders[:] = sorted(d for d in subfolders if d[0] not in '._'
                                   and not is_excluded(os.path.join(folder, d), excludes))
            for name in sorted(names):
                candidate = os.path.join(folder, name)
                if name.endswith(suffixes) and not is_excluded(candidate, excludes):
                    found[os.path.normpath(candidate)] = None
    return list(found)
