"""A student's colcon workspace: where it is, its packages, and whether colcon must build again."""

from __future__ import annotations

import os
import re
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass, field
from pathlib import Path

# Folders that never hold a package's sources.
SKIPPED_FOLDERS = {'build', 'install', 'log', '__pycache__', '.git', 'node_modules', '.venv'}
# Files whose change needs no build (editor and Python leftovers).
IGNORED_SUFFIXES = ('.pyc', '.swp', '~')


class WorkspaceError(Exception):
    """A problem with the workspace, said in one line."""


@dataclass
class Package:
    name: str
    path: Path
    build_type: str
    depends: set[str] = field(default_factory=set)


def find_workspace(start: Path) -> Path:
    """The colcon workspace at start or above it: a folder whose src/ holds a package.xml."""
    start = start.resolve()
    for folder in (start, *start.parents):
        if (folder / 'package.xml').exists():
            continue  # a package's own src/ (C++ sources) is not a workspace
        if (folder / 'src').is_dir() and any(_package_files(folder / 'src', max_depth=3)):
            return folder
    raise WorkspaceError(
        f'{start} is not in a colcon workspace (no src/ folder with a package.xml '
        'here or above); run it in your workspace or give --workspace DIR'
    )


def _package_files(root: Path, max_depth: int) -> list[Path]:
    found = []
    for folder, subfolders, files in os.walk(root):
        depth = len(Path(folder).relative_to(root).parts)
        if 'COLCON_IGNORE' in files:
            subfolders[:] = []
            continue
        if 'package.xml' in files:
            found.append(Path(folder) / 'package.xml')
            subfolders[:] = []  # packages do not nest
            continue
        subfolders[:] = [s for s in subfolders if s not in SKIPPED_FOLDERS and depth < max_depth]
    return found


def read_package(manifest: Path) -> Package:
    try:
        root = ElementTree.parse(manifest).getroot()
    except ElementTree.ParseError as error:
        raise WorkspaceError(f'{manifest} is not valid XML: {error}') from None
    name = (root.findtext('name') or '').strip()
    build_type = (root.findtext('export/build_type') or 'ament_cmake').strip()
    depends = {
        (e.text or '').strip()
        for e in root
        if e.tag in ('depend', 'build_depend', 'exec_depend', 'buildtool_depend')
    }
    return Package(name, manifest.parent, build_type, depends)


def packages(workspace: Path) -> dict[str, Package]:
    """The workspace's packages by name."""
    found = {}
    for manifest in _package_files(workspace / 'src', max_depth=6):
        package = read_package(manifest)
        if package.name:
            found[package.name] = package
    return found


def needed(name: str, available: dict[str, Package]) -> list[str]:
    """The package and the workspace packages it depends on, directly or not."""
    result, todo = [], [name]
    while todo:
        current = todo.pop()
        if current in result or current not in available:
            continue
        result.append(current)
        todo.extend(available[current].depends)
    return result


def newest_source_time(package: Path) -> float:
    newest = 0.0  # files only: Python's __pycache__ folders change folder times without a change
    for folder, subfolders, files in os.walk(package):
        subfolders[:] = [s for s in subfolders if s not in SKIPPED_FOLDERS and not s.endswith('.egg-info')]
        for name in files:
            if not name.endswith(IGNORED_SUFFIXES):
                newest = max(newest, os.lstat(os.path.join(folder, name)).st_mtime)
    return newest


def install_marker(workspace: Path, name: str) -> Path | None:
    """The file colcon writes when it has installed a package (isolated or merged install)."""
    for candidate in (
        workspace / 'install' / name / 'share' / 'colcon-core' / 'packages' / name,
        workspace / 'install' / 'share' / 'colcon-core' / 'packages' / name,
    ):
        if candidate.exists():
            return candidate
    return None


def stale(workspace: Path, names: list[str], available: dict[str, Package]) -> list[str]:
    """Those of the packages never installed or whose sources changed since their last build."""
    result = []
    for name in names:
        marker = install_marker(workspace, name)
        if marker is None or newest_source_time(available[name].path) > os.lstat(marker).st_mtime:
            result.append(name)
    return result


def build_command(names: list[str]) -> list[str]:
    return ['colcon', 'build', '--symlink-install', '--packages-select', *sorted(names)]


ERROR_LINE = re.compile(r'error|Error|ERROR|Traceback|failed|Failed')


# A line that says what went wrong (a Python exception, a compiler or CMake error), rather than
# which command failed (colcon's "Command [...] returned non-zero exit status 1").
CAUSE_LINE = re.compile(r'^(\w+(Error|Exception)\b|CMake Error|.*\berror:)')


def last_error_line(output: str) -> str:
    """The build output's last line that names the error's cause, else its last line naming an error."""
    lines = [line.strip() for line in output.splitlines() if line.strip()]
    for line in reversed(lines):
        if CAUSE_LINE.search(line):
            return line
    summary = re.compile(r'^(Summary:|Failed\s+<<<|Aborted\s+<<<|---|\d+ packages? (failed|aborted))')
    for line in reversed(lines):
        if ERROR_LINE.search(line) and not summary.search(line):
            return line
    return lines[-1] if lines else '(no output)'
