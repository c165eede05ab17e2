"""Substitutions that find things in ROS packages through the ament index (AMENT_PREFIX_PATH)."""

from __future__ import annotations

import os
import shutil
from typing import TYPE_CHECKING, Any

from ament_index_python.packages import PackageNotFoundError, get_package_prefix
from launch.frontend.expose import expose_substitution
from launch.substitution import (
    SomeSubstitutionsType,
    Substitution,
    SubstitutionFailure,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['ExecutableInPackage', 'FindPackage', 'FindPackagePrefix', 'FindPackageShare', 'Parameter']


def package_prefix(package: str) -> str:
    """The install prefix of a package; a missing package is a SubstitutionFailure."""
    try:
        return get_package_prefix(package)
    except PackageNotFoundError as error:
        raise SubstitutionFailure(error.args[0] if error.args else str(error)) from None
    except (ValueError, OSError) as error:
        raise SubstitutionFailure(str(error)) from None


class FindPackage(Substitution):
    """Base of the package look-ups: the package name is performed, then find() gives the path."""

    def __init__(self, package: SomeSubstitutionsType) -> None:
        self.package = normalize_to_list_of_substitutions(package)

    def find(self, package: str) -> str:
        """The path this look-up gives for a package name; each subclass implements it."""
        raise NotImplementedError

    def perform(self, context: LaunchContext) -> str:
        """The path for the performed package name; SubstitutionFailure if the package is not installed."""
        return self.find(perform_substitutions(context, self.package))


class FindPackagePrefix(FindPackage):
    """<prefix> of the package."""

    def find(self, package: str) -> str:
        """The package's install prefix."""
        return package_prefix(package)

    def describe(self) -> str:
        """'FindPackagePrefix(pkg=...)': a readable form without a context."""
        return f'FindPackagePrefix(pkg={describe_substitutions(self.package)})'


class FindPackageShare(FindPackage):
    """<prefix>/share/<package>."""

    def find(self, package: str) -> str:
        """The package's share directory, <prefix>/share/<package> (whether it exists is not checked)."""
        return os.path.join(package_prefix(package), 'share', package)

    def describe(self) -> str:
        """'FindPackageShare(pkg=...)': a readable form without a context."""
        return f'FindPackageShare(pkg={describe_substitutions(self.package)})'


class ExecutableInPackage(Substitution):
    """<prefix>/lib/<package>/<executable>, which must exist and be executable."""

    def __init__(self, executable: SomeSubstitutionsType, package: SomeSubstitutionsType) -> None:
        self.executable = normalize_to_list_of_substitutions(executable)
        self.package = normalize_to_list_of_substitutions(package)

    def perform(self, context: LaunchContext) -> str:
        """The executable's full path.

        Raises SubstitutionFailure if the package, its lib/<package> directory or the executable is missing.
        """
        package = perform_substitutions(context, self.package)
        executable = perform_substitutions(context, self.executable)
        prefix = package_prefix(package)
        libexec = os.path.join(prefix, 'lib', package)
        if not os.path.isdir(libexec):
            raise SubstitutionFailure(f"package '{package}' found at '{prefix}', but libexec directory "
                                      f"'{libexec}' does not exist")
        path = shutil.which(executable, path=libexec)
        if path is None or os.path.dirname(path) != libexec:
            raise SubstitutionFailure(f"executable '{executable}' not found on the libexec directory "
                                      f"'{libexec}' ")
        return path

    def describe(self) -> str:
        """'ExecInPkg(pkg=..., exec=...)': a readable form without a context."""
        return (f'ExecInPkg(pkg={describe_substitutions(self.package)}, '
                f'exec={describe_substitutions(self.executable)})')


Args = list[Any]


@expose_substitution('find-pkg-share', 1)
def _find_pkg_share(package: Args) -> FindPackageShare:
    return FindPackageShare(package)


@expose_substitution('find-pkg-prefix', 1)
def _find_pkg_prefix(package: Args) -> FindPackagePrefix:
    return FindPackagePrefix(package)


@expose_substitution('exec-in-pkg', 2)
def _exec_in_pkg(executable: Args, package: Args) -> ExecutableInPackage:
    return ExecutableInPackage(executable, package)


# Last: the module imports this package's helpers.
from launch_ros.substitutions.parameter import Parameter  # noqa: E402
