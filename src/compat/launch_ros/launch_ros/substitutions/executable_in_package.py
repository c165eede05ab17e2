"""ExecutableInPackage (`$(exec-in-pkg exec pkg)`): an executable of a package, from the ament index."""

from __future__ import annotations

import os
import shutil
from typing import TYPE_CHECKING, Any

from launch.frontend.expose import expose_substitution
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.substitutions import SubstitutionFailure
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.substitutions.find_package import package_prefix

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['ExecutableInPackage']


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
        package = ' + '.join(sub.describe() for sub in self.package)
        executable = ' + '.join(sub.describe() for sub in self.executable)
        return f'ExecInPkg(pkg={package}, exec={executable})'


@expose_substitution('exec-in-pkg', 2)
def _exec_in_pkg(executable: list[Any], package: list[Any]) -> ExecutableInPackage:
    return ExecutableInPackage(executable, package)
