"""Make the interface packages' msg, srv and action modules load each type on its first use.

rosidl_generator_py writes `sensor_msgs/msg/__init__.py` as one import per type, so a node that
publishes a JointState imports all 27 of sensor_msgs' message modules, and with CameraInfo's and
Imu's fixed-size arrays numpy too: 70 ms of a servo module's 200 ms of imports. The rewritten
`__init__.py` names the same types (`__all__`, `dir()`, `from ... import *` as before) and imports a
type's module when the type is first asked for (a module `__getattr__`, PEP 562).

A type with a fixed-size array (CameraInfo's, Imu's covariances, and service_msgs' ServiceEventInfo,
part of every service's type, so of every node's parameter services) imports numpy in its module,
for the array's value: 60-100 ms of CPU at every node's start though most nodes never make one. In
those modules numpy is imported at its first use instead (the module's `numpy` is a stand-in that
imports it and puts it in its place).

Usage: python scripts/lazy_interface_packages.py FOLDER... (make setup: the venv's site-packages
and the workspace's install tree). An `__init__.py` that is not rosidl's list of imports (already
lazy, or edited) is left as it is. Each rewritten one is compiled, as the wheels' modules are.
"""

from __future__ import annotations

import py_compile
import re
import sys
from pathlib import Path

KINDS = ('msg', 'srv', 'action')
GENERATED_LINE = re.compile(
    r'^from (?P<package>[\w.]+)\.(?P<module>_\w+) import (?P<name>\w+)  # noqa: F401$')
MARKER = '# Each type loads on its first use'
NUMPY_IMPORT = 'import numpy  # noqa: E402, I100\n'
NUMPY_AT_FIRST_USE = (
    '# numpy at its first use (scripts/lazy_interface_packages.py, make setup): a stand-in until then.\n'
    'class _NumpyAtFirstUse:\n'
    '    def __getattr__(self, name):\n'
    '        import numpy as module\n'
    "        globals()['numpy'] = module\n"
    '        return getattr(module, name)\n\n\n'
    'numpy = _NumpyAtFirstUse()\n')


def type_modules(init_text: str, package: str) -> dict[str, str] | None:
    """Each type's name and its module, from a generated `__init__.py`; None when it is not one."""
    lines = [line for line in init_text.splitlines() if line.strip()]
    found = [GENERATED_LINE.match(line) for line in lines]
    if not lines or not all(match is not None and match['package'] == package for match in found):
        return None
    return {match['name']: match['module'] for match in found if match is not None}


def lazy_init(types: dict[str, str]) -> str:
    """The text of an `__init__.py` that imports each type's module when the type is asked for."""
    return (f'{MARKER} (scripts/lazy_interface_packages.py, make setup): importing every module\n'
            '# at once cost a node tens of ms at start.\n'
            'import importlib as _importlib\n\n'
            f'_MODULES = {types!r}\n'
            '__all__ = list(_MODULES)\n\n\n'
            'def __getattr__(name):\n'
            '    try:\n'
            '        module = _MODULES[name]\n'
            '    except KeyError:\n'
            "        raise AttributeError(f'module {__name__!r} has no attribute {name!r}') from None\n"
            "    value = getattr(_importlib.import_module(f'{__name__}.{module}'), name)\n"
            '    globals()[name] = value\n'
            '    return value\n\n\n'
            'def __dir__():\n'
            '    return sorted({*globals(), *__all__})\n')


def make_lazy(init: Path) -> bool:
    """Rewrite one generated `__init__.py` (and compile it); whether it was one."""
    package = '.'.join(init.parent.parts[-2:])
    types = type_modules(init.read_text(), package)
    if types is None:
        return False
    init.write_text(lazy_init(types))
    py_compile.compile(str(init), doraise=True)
    return True


def numpy_at_first_use(module: Path) -> None:
    """Make one generated type module import numpy at its first use (and compile it), if it imports it."""
    text = module.read_text()
    if text.count(NUMPY_IMPORT) == 1:
        module.write_text(text.replace(NUMPY_IMPORT, NUMPY_AT_FIRST_USE))
        py_compile.compile(str(module), doraise=True)


def interface_inits(folder: Path) -> list[Path]:
    """The `<package>/<msg|srv|action>/__init__.py` files under a site-packages-like folder."""
    return sorted(init for kind in KINDS for init in folder.glob(f'*/{kind}/__init__.py'))


def main(argv: list[str]) -> int:
    """Rewrite the generated interface modules under each folder of argv; 2 for wrong arguments."""
    missing = [folder for folder in argv if not Path(folder).is_dir()]
    if not argv or missing:
        print('usage: lazy_interface_packages.py FOLDER... (site-packages folders'
              + (f'; not a folder: {", ".join(missing)})' if missing else ')'), file=sys.stderr)
        return 2
    for folder in argv:
        for init in interface_inits(Path(folder)):
            if make_lazy(init) or init.read_text().startswith(MARKER):
                for module in sorted(init.parent.glob('_*.py')):
                    numpy_at_first_use(module)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
