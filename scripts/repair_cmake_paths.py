"""Point the CMake exports of the ROS 2 wheels at this venv instead of the wheel build machine.

The manylinux wheels were built in /opt/python/cp3XX-cp3XX/ and their *.cmake files name that
interpreter's include directory and site-packages (for numpy's headers). Interface packages built
with colcon need those to be this interpreter's. The rewrite is idempotent: a second run finds
nothing left to change.

uv installs a wheel's files as hard links to its cache, so a file is replaced, never written
through: a write through the link changed uv's cached copy, and every later venv on the machine got
the first venv's paths (colcon then failed once that venv was gone). A file that such a write left
naming another venv's paths is pointed at this one like a build machine's.
"""

from __future__ import annotations

import os
import re
import sys
import sysconfig
from pathlib import Path

# An absolute path inside a CMake string or list ("...;...") naming an interpreter's include
# directory, or the site-packages holding numpy's headers: the build machine's or an earlier venv's.
# A path built from a CMake variable (${..._DIR}/../lib/...) is relative to its package: kept.
INCLUDE_DIR = re.compile(r"(?<=[\";])/[^\";$]*/include/python3\.\d+(?=[\";])")
SITE_PACKAGES = re.compile(r"(?<=[\";])/[^\";$]*/lib/python3\.\d+/site-packages(?=/numpy/)")


def repaired_text(text: str, include_dir: str, site_packages: str) -> str:
    """Return text with other interpreters' include and site-packages paths replaced by this venv's."""
    text = INCLUDE_DIR.sub(include_dir, text)
    return SITE_PACKAGES.sub(site_packages, text)


def replace_text(path: Path, text: str) -> None:
    """Give path the new text as a new file: other hard links to the old one keep theirs."""
    temporary = path.with_name(f".{path.name}.repairing")
    temporary.write_text(text, errors="surrogateescape")
    os.chmod(temporary, path.stat().st_mode & 0o7777)
    os.replace(temporary, path)


def repair_tree(prefix: Path, include_dir: str, site_packages: str) -> list[Path]:
    """Rewrite every *.cmake file under prefix that names another interpreter's paths."""
    changed = []
    for cmake_file in prefix.rglob("*.cmake"):
        text = cmake_file.read_text(errors="surrogateescape")
        new_text = repaired_text(text, include_dir, site_packages)
        if new_text != text:
            replace_text(cmake_file, new_text)
            changed.append(cmake_file)
    return changed


def main() -> int:
    """Repair the CMake files of the venv whose python runs this; exit code 2 outside a venv."""
    prefix = Path(sys.prefix)
    if prefix == Path(sys.base_prefix):
        print("repair_cmake_paths: run this with the venv's python, not the system one", file=sys.stderr)
        return 2
    include_dir = sysconfig.get_paths()["include"]
    site_packages = sysconfig.get_paths()["purelib"]
    changed = []
    for subdir in ("share", "lib/cmake"):
        if (prefix / subdir).is_dir():
            changed += repair_tree(prefix / subdir, include_dir, site_packages)
    print(f"repaired other interpreters' paths in {len(changed)} CMake files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
