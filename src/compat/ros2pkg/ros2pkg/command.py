"""`ros2 pkg <verb>`: the command module that ros2cli's command table names for 'pkg'."""

from __future__ import annotations

import argparse
import getpass
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from collections.abc import Callable

from ros2pkg import api
from ros2pkg.create import (
    BUILD_TYPES,
    DEFAULT_LICENSE,
    EMAIL,
    CreateError,
    check_settings,
    plan,
    summary,
    unknown_license_warning,
    write_package,
)
from ros2pkg.templates import LICENSES

DESCRIPTION = 'Various package related sub-commands'
PACKAGE_NOT_FOUND = 'Package not found'


def package_name_completer(**_: object) -> list[str]:
    """Shell completion of package names (argcomplete calls completers with keyword arguments)."""
    return api.get_package_names()


def _package_argument(parser: argparse.ArgumentParser, **kwargs: object) -> None:
    argument = parser.add_argument('package_name', help='The package name', **kwargs)
    argument.completer = package_name_completer  # type: ignore[attr-defined]


def add_arguments(parser: argparse.ArgumentParser, cli_name: str) -> None:
    verbs = parser.add_subparsers(title='Commands', dest='verb',
                                  metavar=f'Call `{cli_name} <command> -h` for more detailed usage.')

    def verb(name: str, main: Callable[[argparse.Namespace], int | str | None],
             help_text: str) -> argparse.ArgumentParser:
        verb_parser = verbs.add_parser(name, help=help_text, description=help_text)
        verb_parser.set_defaults(_verb_main=main)
        return verb_parser

    create = verb('create', main_create, 'Create a new ROS 2 package')
    create.add_argument('package_name', help='The package name')
    create.add_argument('--package-format', '--package_format', type=int, default=3, choices=[2, 3],
                        help='The package.xml format.')
    create.add_argument('--description', default='TODO: Package description',
                        help='The description given in the package.xml')
    license_argument = create.add_argument('--license', default=DEFAULT_LICENSE,
                        help='The license attached to this package; this can be an arbitrary string, but '
                             'a LICENSE file will only be generated if it is one of the supported '
                             "licenses (pass '?' to get a list)")
    license_argument.completer = lambda **_: list(LICENSES)  # type: ignore[attr-defined]
    create.add_argument('--destination-directory', default=os.curdir,
                        help='Directory where to create the package directory')
    # Checked in main_create rather than with `choices`, to answer typos with a suggestion.
    build_type = create.add_argument('--build-type', default='ament_cmake',
                                     metavar='{' + ','.join(BUILD_TYPES) + '}',
                                     help='The build type to process the package with')
    build_type.completer = lambda **_: list(BUILD_TYPES)  # type: ignore[attr-defined]
    create.add_argument('--dependencies', nargs='+', default=[], help='list of dependencies')
    create.add_argument('--maintainer-email', help='email address of the maintainer of this package')
    create.add_argument('--maintainer-name', default=_login_name(),
                        help='name of the maintainer of this package')
    create.add_argument('--node-name', help='name of the empty executable')
    create.add_argument('--library-name', help='name of the empty library')

    executables = verb('executables', main_executables, 'Output a list of package specific executables')
    _package_argument(executables, nargs='?')
    executables.add_argument('--full-path', action='store_true', default=False,
                             help='Show full path of each executable')

    verb('list', main_list, 'Output a list of available packages')

    prefix = verb('prefix', main_prefix, 'Output the prefix path of a package')
    _package_argument(prefix)
    prefix.add_argument('--share', action='store_true',
                        help='Show share directory for the package')

    xml = verb('xml', main_xml, 'Output the XML of the package manifest or a specific tag')
    _package_argument(xml)
    xml.add_argument('-t', '--tag', help="The package's xml's tag to print")


def main(args: argparse.Namespace) -> int | str | None:
    verb_main = getattr(args, '_verb_main', None)
    if verb_main is None:
        args._parser.print_help()
        return 0
    return verb_main(args)


def main_list(args: argparse.Namespace) -> int:
    for name in api.get_package_names():
        print(name)
    return 0


def main_executables(args: argparse.Namespace) -> int | str:
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
    lookup = api.get_share_directory if args.share else api.get_prefix_path
    path = lookup(args.package_name)
    if path is None:
        return PACKAGE_NOT_FOUND
    print(path)
    return 0


def main_xml(args: argparse.Namespace) -> int | str:
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
    git = shutil.which('git')
    if git is None:
        return None
    try:
        result = subprocess.run([git, 'config', 'user.email'], capture_output=True, text=True,
                                timeout=5, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return result.stdout.strip() or None
