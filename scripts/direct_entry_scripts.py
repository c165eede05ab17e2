"""Rewrite the workspace's console scripts to import their entry point directly.

`colcon build --symlink-install` installs a package's console scripts (`ros2`, `owl`, servo_sim,
the course's nodes) with setuptools' develop template, which looks the entry point up through
importlib.metadata: importing it and reading the distribution's metadata cost 20-25 ms of CPU at
every start, and the suite starts some 1,400 of them (every `ros2` call, every node). The rewritten
script imports `module:attr` from the package's entry_points.txt and calls it, as pip's scripts do.

Usage: python scripts/direct_entry_scripts.py WORKSPACE (run by make setup after colcon; a script
already rewritten, or not setuptools', is left as it is, and one whose entry point cannot be found
is left working as setuptools wrote it, with a warning).
"""

from __future__ import annotations

import configparser
import re
import sys
from pathlib import Path

MARKER = '# EASY-INSTALL-ENTRY-SCRIPT'
LOAD = re.compile(r"load_entry_point\('([^']+)', '([^']+)', '([^']+)'\)")
ENTRY = re.compile(r'^\s*(?P<module>[\w.]+)\s*:\s*(?P<attr>[\w.]+)\s*(\[.*\])?\s*$')


def normalised(name: str) -> str:
    """A distribution's name as its egg-info folder spells it (olive-sim and olive_sim are one)."""
    return re.sub(r'[-_.]+', '_', name).lower()


def entry_points_files(workspace: Path) -> dict[str, Path]:
    """Each distribution of the workspace (normalised name) and its entry_points.txt.

    A --symlink-install build keeps the egg-info in build/<package>; a copied one, in the install
    tree's site-packages.
    """
    found: dict[str, Path] = {}
    for path in [*workspace.glob('build/*/*.egg-info/entry_points.txt'),
                 *workspace.glob('install/*/lib/python*/site-packages/*.egg-info/entry_points.txt')]:
        found.setdefault(normalised(path.parent.name.removesuffix('.egg-info').split('-')[0]), path)
    return found


def entry_point(entry_points_txt: str, group: str, name: str) -> tuple[str, str]:
    """(module, attr) of the entry point `name` in `group` of an entry_points.txt's text.

    LookupError when there is none, ValueError when the text or the value is not what it should be.
    """
    parser = configparser.ConfigParser(delimiters=('=',), interpolation=None)
    parser.optionxform = str  # type: ignore[assignment,method-assign]  # names are case-sensitive
    try:
        parser.read_string(entry_points_txt)
    except configparser.Error as error:
        raise ValueError(f'not an entry_points.txt: {str(error).splitlines()[0]}') from None
    if not parser.has_option(group, name):
        raise LookupError(f'its entry_points.txt declares no {name} in [{group}]')
    value = parser[group][name]
    match = ENTRY.match(value)
    if match is None:
        raise ValueError(f'{group} {name} = {value!r} is not module:attr')
    return match['module'], match['attr']


def direct_script(shebang: str, dist: str, name: str, module: str, attr: str) -> str:
    """The text of a script that calls module's attr (which may be dotted), as pip's scripts do."""
    first = attr.split('.')[0]
    return (f'{shebang}\n'
            f'# {name} of {dist} ({module}:{attr}), imported directly: written by make setup\n'
            '# (scripts/direct_entry_scripts.py) over setuptools\' script, which took 20 ms to find it.\n'
            'import sys\n\n'
            f'from {module} import {first}\n\n'
            "if __name__ == '__main__':\n"
            f'    sys.exit({attr}())\n')


def rewrite(script: Path, entry_points: dict[str, Path]) -> None:
    """Rewrite one setuptools develop script in place (any other script is left as it is)."""
    try:
        text = script.read_text()
    except (UnicodeDecodeError, OSError):
        return  # a binary, or a link to nothing
    found = LOAD.search(text) if MARKER in text else None
    if found is None:
        return
    dist, group, name = found.groups()
    source = entry_points.get(normalised(dist))
    if source is None:
        raise LookupError(f'{script}: no entry_points.txt of {dist} in the workspace')
    module, attr = entry_point(source.read_text(), group, name)
    script.write_text(direct_script(text.split('\n', 1)[0], dist, name, module, attr))


def main(argv: list[str]) -> int:
    """Rewrite the console scripts of the workspace argv[0]; 2 for wrong arguments, else 0."""
    if len(argv) != 1 or not Path(argv[0]).is_dir():
        print('usage: direct_entry_scripts.py WORKSPACE (a built colcon workspace)', file=sys.stderr)
        return 2
    workspace = Path(argv[0])
    entry_points = entry_points_files(workspace)
    scripts = [path for pattern in ('install/*/lib/*/*', 'install/*/bin/*')
               for path in workspace.glob(pattern) if path.is_file() and not path.is_symlink()]
    for script in scripts:
        try:
            rewrite(script, entry_points)
        except (LookupError, ValueError) as error:
            print(f'setup: {script} left as setuptools wrote it: {error}', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
