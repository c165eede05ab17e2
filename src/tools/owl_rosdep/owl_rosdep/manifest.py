"""The packages rosdep looks at and the dependency keys their package.xml files declare."""

from __future__ import annotations

import os

from ament_index_python.packages import PackageNotFoundError, get_package_share_directory
from catkin_pkg.package import InvalidPackage, Package, parse_package
from catkin_pkg.packages import find_packages

# The dependency types of `rosdep --dependency-types`, and the package.xml lists they read.
DEPENDENCY_TYPES: dict[str, str] = {
    'build': 'build_depends',
    'buildtool': 'buildtool_depends',
    'build_export': 'build_export_depends',
    'buildtool_export': 'buildtool_export_depends',
    'exec': 'exec_depends',
    'test': 'test_depends',
    'doc': 'doc_depends',
}


class ManifestError(Exception):
    """A path or package that cannot be read; str() is the line for the user."""


def packages_in_paths(paths: list[str]) -> list[Package]:
    """Every package under the given folders (COLCON_IGNORE etc. respected), conditions evaluated."""
    found: dict[str, Package] = {}
    for path in paths:
        if not os.path.isdir(path):
            raise ManifestError(f"given path '{path}' does not exist or is not a folder")
        try:
            packages = find_packages(path)
        except (InvalidPackage, RuntimeError) as error:  # invalid XML; one name in two folders
            raise ManifestError(_one_line(error)) from None
        for package in packages.values():
            if package.name in found:
                raise ManifestError(f"two packages are named '{package.name}': "
                                    f'{os.path.dirname(found[package.name].filename)} and '
                                    f'{os.path.dirname(package.filename)}')
            package.evaluate_conditions(os.environ)
            found[package.name] = package
    return sorted(found.values(), key=lambda package: package.name)


def installed_packages(names: list[str]) -> list[Package]:
    """The installed packages of those names, read from <share>/<name>/package.xml."""
    packages = []
    for name in names:
        try:
            share = get_package_share_directory(name)
        except (PackageNotFoundError, ValueError):
            raise ManifestError(f"package '{name}' is not installed (to check a source folder, give "
                                '--from-paths <folder>)') from None
        try:
            package = parse_package(share)
        except InvalidPackage as error:
            raise ManifestError(_one_line(error)) from None
        package.evaluate_conditions(os.environ)
        packages.append(package)
    return packages


def dependency_keys(package: Package, types: list[str]) -> list[str]:
    """The keys of the package's dependencies of the given types, in order, each once."""
    keys: dict[str, None] = {}
    for dependency_type in types:
        for dependency in getattr(package, DEPENDENCY_TYPES[dependency_type]):
            if dependency.evaluated_condition is not False:
                keys.setdefault(dependency.name)
    return list(keys)


def _one_line(error: Exception) -> str:
    return ' '.join(str(error).split())
