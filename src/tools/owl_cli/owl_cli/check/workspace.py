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
    """A package of the workspace as its package.xml gives it: name, folder, build type, dependencies."""

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
    """The package a package.xml describes; WorkspaceError when the file is not valid XML.

    The build type is ament_cmake unless the file exports another; depends holds the names of its
    depend, build_depend, exec_depend and buildtool_depend tags.
    """
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
    """The newest modification time (s since the epoch) of the package folder's source files; 0.0 for none."""
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
    """The colcon command that builds just these packages (symlink install, as the course does)."""
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


def executables(workspace: Path, package: str) -> list[str]:
    """The executables `ros2 run` finds for a package of the workspace (isolated or merged install)."""
    install = workspace / 'install'
    for folder in (install / package / 'lib' / package, install / 'lib' / package):
        if folder.is_dir():
            return sorted(p.name for p in folder.iterdir() if p.is_file() and os.access(p, os.X_OK))
    return []


# Words a student's executable name may use for the 3.6 exercise's subjects and roles.
SUBJECT_WORDS = {'currency': ('currency', 'money', 'euro', 'exchange'), 'factorial': ('factorial', 'fact')}
ROLE_WORDS = {'server': ('server', 'service', 'srv'), 'client': ('client', 'cli')}


def find_executable(names: list[str], subject: str, role: str) -> str | None:
    """The executable for a subject ('currency') and role ('server') among names; None when none fits.

    The reference name (currency_server) if there is one, else the first whose name has a word of
    each (SUBJECT_WORDS, ROLE_WORDS).
    """
    if f'{subject}_{role}' in names:
        return f'{subject}_{role}'
    for name in sorted(names):
        lower = name.lower()
        if any(w in lower for w in SUBJECT_WORDS[subject]) and any(w in lower for w in ROLE_WORDS[role]):
            return name
    return None


def parameter_files(workspace: Path, home: Path | None = None) -> list[Path]:
    """YAML files with a `ros__parameters` key (what `ros2 param dump` writes).

    They are looked for in the workspace (outside build/install/log) and, when home is given, in
    ~/Documents, where section 3.7.1 saves turtlesim.yaml.
    """
    found = []
    roots = [(workspace, 4)] + ([(home / 'Documents', 1)] if home is not None else [])
    for root, max_depth in roots:
        if not root.is_dir():
            continue
        for folder, subfolders, files in os.walk(root):
            depth = len(Path(folder).relative_to(root).parts)
            subfolders[:] = sorted(
                s for s in subfolders if s not in SKIPPED_FOLDERS and depth + 1 < max_depth
            )
            for name in sorted(files):
                path = Path(folder) / name
                if name.endswith(('.yaml', '.yml')) and _has_ros_parameters(path):
                    found.append(path)
    return found


def _has_ros_parameters(path: Path) -> bool:
    try:
        return 'ros__parameters' in path.read_text(errors='replace')[:100_000]
    except OSError:
        return False


def read_parameter_file(text: str) -> dict[str, dict[str, object]]:
    """{node name: {parameter: value}} of a parameter file; nested keys joined with '.' as ROS does.

    Raises ValueError with a one-line reason when the text is not such a file.
    """
    import yaml

    try:
        content = yaml.safe_load(text)
    except yaml.YAMLError as error:
        raise ValueError(f'not valid YAML: {str(error).splitlines()[0]}') from None
    if not isinstance(content, dict):
        raise ValueError('the file must map node names to their ros__parameters')
    nodes: dict[str, dict[str, object]] = {}
    for node, section in content.items():
        if not isinstance(section, dict) or not isinstance(section.get('ros__parameters'), dict):
            raise ValueError(f"'{node}' has no ros__parameters mapping under it")
        flat: dict[str, object] = {}
        _flatten(section['ros__parameters'], '', flat)
        nodes[str(node)] = flat
    return nodes


def _flatten(values: dict, prefix: str, into: dict[str, object]) -> None:
    for key, value in values.items():
        name = f'{prefix}{key}'
        if isinstance(value, dict):
            _flatten(value, name + '.', into)
        else:
            into[name] = value


def package_layout_problems(package: Path, name: str) -> list[str]:
    """What an `ros2 pkg create NAME --build-type ament_python` package misses, in its own words."""
    expected = {
        'package.xml': package / 'package.xml',
        'setup.py': package / 'setup.py',
        'setup.cfg': package / 'setup.cfg',
        f'resource/{name}': package / 'resource' / name,
        f'{name}/__init__.py': package / name / '__init__.py',
    }
    return [f'{label} is missing' for label, path in expected.items() if not path.exists()]
