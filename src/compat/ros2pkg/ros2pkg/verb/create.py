"""`ros2 pkg create`: a new ROS 2 package, as upstream writes it."""

from __future__ import annotations

import argparse
import getpass
import os
import shutil
import sys

from ros2cli.verb import VerbExtension


class CreateVerb(VerbExtension):
    """Create a new ROS 2 package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add create's arguments; the build type is checked in main_create, to suggest a fix for a typo."""
        # Lazy: ros2pkg.api.create imports dataclasses (inspect), and `ros2 pkg -h` imports this module.
        from ros2pkg.api.create import BUILD_TYPES, DEFAULT_LICENSE
        from ros2pkg.templates import LICENSES

        parser.add_argument('package_name', help='The package name')
        parser.add_argument('--package-format', '--package_format', type=int, default=3, choices=[2, 3],
                            help='The package.xml format.')
        parser.add_argument('--description', default='TODO: Package description',
                            help='The description given in the package.xml')
        license_argument = parser.add_argument(
            '--license', default=DEFAULT_LICENSE,
            help='The license attached to this package; this can be an arbitrary string, but a LICENSE '
                 "file will only be generated if it is one of the supported licenses (pass '?' to get a "
                 'list)')
        license_argument.completer = lambda **_: list(LICENSES)  # type: ignore[attr-defined]
        parser.add_argument('--destination-directory', default=os.curdir,
                            help='Directory where to create the package directory')
        # Checked in main rather than with `choices`, to answer typos with a suggestion.
        build_type = parser.add_argument('--build-type', default='ament_cmake',
                                         metavar='{' + ','.join(BUILD_TYPES) + '}',
                                         help='The build type to process the package with')
        build_type.completer = lambda **_: list(BUILD_TYPES)  # type: ignore[attr-defined]
        parser.add_argument('--dependencies', nargs='+', default=[], help='list of dependencies')
        parser.add_argument('--maintainer-email', help='email address of the maintainer of this package')
        parser.add_argument('--maintainer-name', default=_login_name(),
                            help='name of the maintainer of this package')
        parser.add_argument('--node-name', help='name of the empty executable')
        parser.add_argument('--library-name', help='name of the empty library')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Create the package: see main_create."""
        return main_create(args)


def main_create(args: argparse.Namespace) -> int | str:
    """Create a package as the arguments say, printing what upstream's `ros2 pkg create` prints.

    Returns 0 on success.  A refused request returns the CreateError's message (exit code 1) or, for
    a usage error, prints it to stderr as argparse would and returns its exit code (2).
    """
    # Lazy: ros2pkg.api.create imports dataclasses (inspect), and `ros2 pkg -h` imports this module.
    from ros2pkg.api.create import (
        EMAIL,
        CreateError,
        check_settings,
        plan,
        summary,
        unknown_license_warning,
        write_package,
    )
    from ros2pkg.templates import LICENSES

    if args.license == '?':
        print('Supported licenses:\n' + '\n'.join(LICENSES))
        return 0
    try:
        settings = check_settings(
            name=args.package_name, build_type=args.build_type, dependencies=args.dependencies,
            description=args.description, license_name=args.license,
            maintainer_name=args.maintainer_name,
            maintainer_email=args.maintainer_email,
            node_name=args.node_name, library_name=args.library_name,
            package_format=args.package_format, destination=args.destination_directory,
            warn=lambda line: print(line, file=sys.stderr))
        git_email = _git_email() if args.maintainer_email is None else None
        if git_email and EMAIL.fullmatch(git_email):
            settings.maintainer_email = git_email
        for line in summary(settings, args.destination_directory):
            print(line)
        write_package(plan(settings, args.destination_directory), print)
    except CreateError as error:
        if error.exit_code == 1:
            return str(error)
        print(f'ros2 pkg create: error: {error}', file=sys.stderr)
        return error.exit_code
    if settings.license not in LICENSES:
        print(unknown_license_warning(settings.license))
    return 0


def _login_name() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):  # no passwd entry and no LOGNAME/USER: e.g. some containers
        return 'user'


def _git_email() -> str | None:
    """`git config user.email`, as upstream uses when --maintainer-email is not given."""
    import subprocess  # lazy: needed only without --maintainer-email; `ros2 pkg -h` imports this module
    git = shutil.which('git')
    if git is None:
        return None
    try:
        result = subprocess.run([git, 'config', 'user.email'], capture_output=True, text=True,
                                timeout=5, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return result.stdout.strip() or None
