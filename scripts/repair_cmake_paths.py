"""Point the CMake exports of the ROS 2 wheels at this venv instead of the wheel build machine.

The manylinux wheels were built in /opt/python/cp3XX-cp3XX/ and their *.cmake files name that
interpreter's include directory and site-packages (for numpy's headers). Interface packages built
with colcon need those to be this interpreter's. The rewrite is idempotent: a second run finds
nothing left to change.
"""

from __future__ import annotations

import re
import sys
import sysconfig
from pathlib import Path

BUILD_MACHINE_PREFIX = re.compile(r"/opt/python/cp3\d+-cp3\d+")
INCLUDE_DIR = re.compile(r"/opt/python/cp3\d+-cp3\d+/include/python3\.\d+")
SITE_PACKAGES = re.compile(r"/opt/python/cp3\d+-cp3\d+/lib/python3\.\d+/site-packages")


def repaired_text(text: str, include_dir: str, site_packages: str) -> str:
    """Return text with the wheel build machine's paths replaced by this venv's."""
    text = INCLUDE_DIR.sub(include_dir, text)
    return SITE_PACKAGES.sub(site_packages, text)


def repair_tree(prefix: Path, include_dir: str, site_packages: str) -> list[Path]:
    """Rewrite every *.cmake file under prefix that still names the build machine."""
    changed = []
    for cmake_file in prefix.rglob("*.cmake"):
        text = cmake_file.read_text(errors="surrogateescape")
        if not BUILD_MACHINE_PREFIX.search(text):
            continue
        new_text = repaired_text(text, include_dir, site_packages)
        if new_text != text:
            cmake_file.write_text(new_text, errors="surrogateescape")
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
    print(f"repaired build-machine paths in {len(changed)} CMake files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
