"""Turn rosdep keys into "already there", "pip install <name>==<version>" or a reason why not.

A key is satisfied by an installed ROS package (ament index), an importable Python module
(`python3-<name>` keys) or a tool on PATH. A missing ROS package resolves to its `ros-<name>`
wheel at the version requirements.txt pins (the project's source of truth), else at the version
of the wheel set this package ships (ros_wheels.tsv); a missing Python key resolves only to a pin.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from ament_index_python.packages import get_packages_with_prefixes
from packaging.requirements import InvalidRequirement, Requirement
from packaging.utils import canonicalize_name

WHEEL_TABLE = Path(__file__).with_name('ros_wheels.tsv')

# python3-* keys whose module or pip name is not simply the part after 'python3-'.
PYTHON_KEYS: dict[str, tuple[str, str]] = {
    # key: (module to import, pip distribution)
    'python3-yaml': ('yaml', 'PyYAML'),
    'python3-pil': ('PIL', 'pillow'),
    'python3-dateutil': ('dateutil', 'python-dateutil'),
    'python3-catkin-pkg': ('catkin_pkg', 'catkin-pkg'),
    'python3-catkin-pkg-modules': ('catkin_pkg', 'catkin-pkg'),
    'python3-empy': ('em', 'empy'),
    'python3-lark': ('lark', 'lark-parser'),
    'python3-lark-parser': ('lark', 'lark-parser'),
    # The GUI build (cv2.imshow windows); bootstrap.sh adds its headless twin apart.
    'python3-opencv': ('cv2', 'opencv-python'),
    'python3-pkg-resources': ('pkg_resources', 'setuptools'),
    'python3-serial': ('serial', 'pyserial'),
    'python3-pygments': ('pygments', 'Pygments'),
    'python3-colcon-common-extensions': ('colcon_core', 'colcon-common-extensions'),
}
# Keys for programs rather than Python modules or ROS packages; pip cannot install these.
TOOL_KEYS: dict[str, str] = {
    'python3': 'python3',
    'python3-dev': 'python3',
    'cmake': 'cmake',
    'git': 'git',
    'pkg-config': 'pkg-config',
}


@dataclass(frozen=True)
class Resolution:
    """What one key needs: nothing (satisfied), a pip requirement, or an error for the user."""

    key: str
    satisfied: bool = False
    pip: str | None = None
    error: str | None = None


def wheel_name(key: str) -> str:
    """The PyPI name of a ROS package's wheel: nav_msgs -> ros-nav-msgs."""
    return 'ros-' + key.replace('_', '-')


def load_pins(requirements: Path | None) -> dict[str, str]:
    """Exact pins (canonical name -> version) from a requirements file, for this Python only."""
    pins: dict[str, str] = {}
    if requirements is None or not requirements.is_file():
        return pins
    for line in requirements.read_text(encoding='utf-8').splitlines():
        line = line.split(' #', 1)[0].strip()
        if not line or line.startswith(('#', '-')):
            continue
        try:
            requirement = Requirement(line)
        except InvalidRequirement:
            continue
        if requirement.marker is not None and not requirement.marker.evaluate():
            continue
        exact = [spec.version for spec in requirement.specifier if spec.operator == '==']
        if exact:
            pins[canonicalize_name(requirement.name)] = exact[0]
    return pins


def load_wheel_table(path: Path = WHEEL_TABLE) -> dict[str, str]:
    """The table of ROS wheels this package ships (canonical name -> version), for keys not pinned."""
    table: dict[str, str] = {}
    for line in path.read_text(encoding='utf-8').splitlines():
        if line and not line.startswith('#'):
            name, version = line.split('\t')
            table[canonicalize_name(name)] = version
    return table


def default_requirements() -> Path | None:
    """requirements.txt of the Owl Kit Lab checkout that env.sh set up (OWL_ROOT), if any."""
    root = os.environ.get('OWL_ROOT')
    return Path(root) / 'requirements.txt' if root else None


def module_available(module: str) -> bool:
    """Whether a Python module can be imported here (found without importing it)."""
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        return False


class Resolver:
    """Resolves keys against this environment; the lookups are injectable for tests."""

    def __init__(self, pins: Mapping[str, str], wheels: Mapping[str, str],
                 installed_packages: Iterable[str] | None = None,
                 has_module: Callable[[str], bool] = module_available,
                 has_program: Callable[[str], bool] = lambda name: shutil.which(name) is not None):
        self.pins = dict(pins)
        self.wheels = dict(wheels)
        self.installed = set(get_packages_with_prefixes() if installed_packages is None
                             else installed_packages)
        self.has_module = has_module
        self.has_program = has_program

    def resolve(self, key: str) -> Resolution:
        """What the key needs: installed ROS package, tool on PATH, Python module, else a pin or wheel."""
        if key in self.installed:
            return Resolution(key, satisfied=True)
        if key in TOOL_KEYS:
            if self.has_program(TOOL_KEYS[key]):
                return Resolution(key, satisfied=True)
            return Resolution(key, error=f'[{key}] is a system program that pip cannot install: '
                                         "install it with the system's package manager")
        if key.startswith('python3-'):
            return self._resolve_python(key)
        return self._resolve_ros(key)

    def _resolve_python(self, key: str) -> Resolution:
        bare = key[len('python3-'):]
        module, distribution = PYTHON_KEYS.get(key, (bare.replace('-', '_'), bare))
        if self.has_module(module):
            return Resolution(key, satisfied=True)
        version = self.pins.get(canonicalize_name(distribution))
        if version is None:
            return Resolution(key, error=f'Cannot locate rosdep definition for [{key}] (the Python module '
                                         f"'{module}' is missing and requirements.txt pins no "
                                         f"'{distribution}')")
        return Resolution(key, pip=f'{distribution}=={version}')

    def _resolve_ros(self, key: str) -> Resolution:
        name = wheel_name(key)
        canonical = canonicalize_name(name)
        version = self.pins.get(canonical) or self.wheels.get(canonical)
        if version is None:
            return Resolution(key, error=f'Cannot locate rosdep definition for [{key}]')
        return Resolution(key, pip=f'{name}=={version}')
