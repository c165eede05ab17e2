"""`ros2 pkg <verb>`: the command and its verbs.

`ros2` finds them through this package's entry points ('ros2cli.command' and 'ros2pkg.verb' in
setup.py).
"""

from __future__ import annotations

import argparse
import os
import sys

from ros2cli.command import VerbCommand
from ros2cli.verb import VerbExtension

# Everything else is imported where it is used: `ros2 -h` imports this module for its docstrings.

PACKAGE_NOT_FOUND = 'Package not found'


def package_name_completer(**_: object) -> list[str]:
    """Shell completion of package names (argcomplete calls completers with keyword arguments)."""
    from ros2pkg import api
    return api.get_package_names()


def _package_argument(parser: argparse.ArgumentParser, nargs: str | None = None) -> None:
    from ros2cli.completion import with_completer
    with_completer(parser.add_argument('package_name', help='The package name', nargs=nargs),
                   package_name_completer)


class PkgCommand(VerbCommand):
    """Various package related sub-commands."""

    VERB_GROUP = 'ros2pkg.verb'


class CreateVerb(VerbExtension):
    """Create a new ROS 2 package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add create's arguments; the build type is checked in main_create, to suggest a fix for a typo."""
        from ros2pkg.create import BUILD_TYPES, DEFAULT_LICENSE
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


class ExecutablesVerb(VerbExtension):
    """Output a list of package specific executables."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add an optional package name (none: every package) and --full-path."""
        _package_argument(parser, nargs='?')
        parser.add_argument('--full-path', action='store_true', default=False,
                            help='Show full path of each executable')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """List the executables: see main_executables."""
        return main_executables(args)


class ListVerb(VerbExtension):
    """Output a list of available packages."""

    def main(self, *, args: argparse.Namespace) -> int:
        """List the packages: see main_list."""
        return main_list(args)


class PrefixVerb(VerbExtension):
    """Output the prefix path of a package."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and --share."""
        _package_argument(parser)
        parser.add_argument('--share', action='store_true', help='Show share directory for the package')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the package's prefix: see main_prefix."""
        return main_prefix(args)


class XmlVerb(VerbExtension):
    """Output the XML of the package manifest or a specific tag."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the package name and -t/--tag."""
        _package_argument(parser)
        parser.add_argument('-t', '--tag', help="The package's xml's tag to print")

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the manifest or a tag's text: see main_xml."""
        return main_xml(args)


def main_list(args: argparse.Namespace) -> int:
    """Print the name of every package on AMENT_PREFIX_PATH, one a line, sorted; always 0."""
    from ros2pkg import api
    for name in api.get_package_names():
        print(name)
    return 0


def main_executables(args: argparse.Namespace) -> int | str:
    """Print '<package> <executable>' (or the full path) for one package's executables, or every package's.

    Returns an error message for a package that is not found.
    """
    from ros2pkg import api
    names = [args.package_name] if args.package_name else api.get_package_names()
    for name in names:
        try:
            paths = api.get_executable_paths(name)
        except api.PackageNotFound:
            return f"Package '{name}' not found"
        for path in paths:
            print(path if args.full_path else f'{name} {os.path.basename(path)}')
    return 0


def main_prefix(args: argparse.Namespace) -> int | str:
    """Print a package's install prefix, or its share directory with --share; PACKAGE_NOT_FOUND if missing."""
    from ros2pkg import api
    lookup = api.get_share_directory if args.share else api.get_prefix_path
    path = lookup(args.package_name)
    if path is None:
        return PACKAGE_NOT_FOUND
    print(path)
    return 0


def main_xml(args: argparse.Namespace) -> int | str:
    """Print a package's package.xml, or the text of each element that --tag finds in it.

    Returns an error message when the package, its manifest or the tag is not found, or it cannot be read.
    """
    import xml.etree.ElementTree as ET

    from ros2pkg import api
    share = api.get_share_directory(args.package_name)
    if share is None:
        return PACKAGE_NOT_FOUND
    manifest = os.path.join(share, 'package.xml')
    if not os.path.isfile(manifest):
        return 'Package xml manifest not found'
    try:
        tree = ET.parse(manifest)
    except (ET.ParseError, OSError) as error:
        return f'Package xml manifest {manifest} cannot be read: {error}'
    if args.tag is None:
        ET.dump(tree)
        return 0
    try:
        elements = tree.getroot().findall(args.tag)
    except (SyntaxError, KeyError, TypeError):  # not an ElementPath expression, e.g. '['
        elements = []
    if not elements:
        return 'XML tag not found'
    for element in elements:
        print(element.text)
    return 0


def main_create(args: argparse.Namespace) -> int | str:
    """Create a package as the arguments say, printing what upstream's `ros2 pkg create` prints.

    Returns 0 on success.  A refused request returns the CreateError's message (exit code 1) or, for
    a usage error, prints it to stderr as argparse would and returns its exit code (2).
    """
    from ros2pkg.create import (
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
    import getpass
    try:
        return getpass.getuser()
    except (KeyError, OSError):  # no passwd entry and no LOGNAME/USER: e.g. some containers
        return 'user'


def _git_email() -> str | None:
    """`git config user.email`, as upstream uses when --maintainer-email is not given."""
    import shutil
    import subprocess
    git = shutil.which('git')
    if git is None:
        return None
    try:
        result = subprocess.run([git, 'config', 'user.email'], capture_output=True, text=True,
                                timeout=5, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return result.stdout.strip() or None
