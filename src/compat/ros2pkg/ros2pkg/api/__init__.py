"""Installed packages as the ament index sees them: names, prefixes, executables, manifests.

Also what several `ros2 pkg` verbs share: the package name argument, completed in the shell.
"""

import argparse
import os

from ament_index_python.packages import (
    PackageNotFoundError,
    get_package_prefix,
    get_package_share_directory,
    get_packages_with_prefixes,
)
from ros2cli.completion import with_completer

PACKAGE_NOT_FOUND = 'Package not found'


class PackageNotFound(Exception):
    """No package of that name is registered in the ament index."""

    def __init__(self, package_name: str):
        super().__init__(package_name)
        self.package_name = package_name


def get_package_names() -> list[str]:
    """Every package registered on AMENT_PREFIX_PATH, sorted."""
    return sorted(get_packages_with_prefixes())


def get_prefix_path(package_name: str) -> str | None:
    """The install prefix of a package, or None when it is unknown (or not a valid name)."""
    try:
        return get_package_prefix(package_name)
    except (PackageNotFoundError, ValueError):
        return None


def get_share_directory(package_name: str) -> str | None:
    """<prefix>/share/<package>, or None when the package is unknown."""
    try:
        return get_package_share_directory(package_name)
    except (PackageNotFoundError, ValueError):
        return None


def get_executable_paths(package_name: str) -> list[str]:
    """Absolute paths of the executables in <prefix>/lib/<package>, sorted; hidden folders skipped."""
    prefix = get_prefix_path(package_name)
    if prefix is None:
        raise PackageNotFound(package_name)
    base = os.path.join(prefix, 'lib', package_name)
    executables = []
    for folder, subfolders, files in os.walk(base):
        subfolders[:] = sorted(name for name in subfolders if not name.startswith('.'))
        for name in files:
            path = os.path.join(folder, name)
            if os.path.isfile(path) and os.access(path, os.X_OK):
                executables.append(path)
    return sorted(executables)


def package_name_completer(**_: object) -> list[str]:
    """Shell completion of package names (argcomplete calls completers with keyword arguments)."""
    return get_package_names()


def _package_argument(parser: argparse.ArgumentParser, nargs: str | None = None) -> None:
    with_completer(parser.add_argument('package_name', help='The package name', nargs=nargs),
                   package_name_completer)
