"""FindPackagePrefix and FindPackageShare (`$(find-pkg-prefix)`, `$(find-pkg-share)`): the ament index."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from ament_index_python.packages import PackageNotFoundError, get_package_prefix
from launch.frontend.expose import expose_substitution
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.substitutions import SubstitutionFailure
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['FindPackage', 'FindPackagePrefix', 'FindPackageShare']


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
        return f"FindPackagePrefix(pkg={' + '.join(sub.describe() for sub in self.package)})"


class FindPackageShare(FindPackage):
    """<prefix>/share/<package>."""

    def find(self, package: str) -> str:
        """The package's share directory, <prefix>/share/<package> (whether it exists is not checked)."""
        return os.path.join(package_prefix(package), 'share', package)

    def describe(self) -> str:
        """'FindPackageShare(pkg=...)': a readable form without a context."""
        return f"FindPackageShare(pkg={' + '.join(sub.describe() for sub in self.package)})"


@expose_substitution('find-pkg-share', 1)
def _find_pkg_share(package: list[Any]) -> FindPackageShare:
    return FindPackageShare(package)


@expose_substitution('find-pkg-prefix', 1)
def _find_pkg_prefix(package: list[Any]) -> FindPackagePrefix:
    return FindPackagePrefix(package)
