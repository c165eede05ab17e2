"""`rosdep`: install and check the dependencies of ROS packages, with pip and the pinned ROS wheels.

Same commands, options and messages as upstream rosdep for what the course uses
(`rosdep install -i --from-paths src --rosdistro <distro> -y`); keys resolve against this
environment (see resolve.py) instead of a rosdistro database, so `init` and `update` have
nothing to do.
"""

from __future__ import annotations

import argparse
import os
import shlex
import subprocess
import sys
from dataclasses import dataclass, field

from owl_rosdep.manifest import (
    DEPENDENCY_TYPES,
    ManifestError,
    dependency_keys,
    installed_packages,
    packages_in_paths,
)
from owl_rosdep.resolve import Resolution, Resolver, default_requirements, load_pins, load_wheel_table

SUCCESS = '#All required rosdeps installed successfully'
NOTHING_TO_SET_UP = ('rosdep {verb}: nothing to do here. This rosdep needs no sources list or '
                     'database: it resolves keys from the installed packages and the ROS wheels '
                     'pinned in requirements.txt.')


@dataclass
class Plan:
    """The outcome of resolving every key of the selected packages."""

    pip: list[str] = field(default_factory=list)  # requirements to install, each once, in order
    errors: list[str] = field(default_factory=list)  # '<package>: <reason>' lines


def build_parser() -> argparse.ArgumentParser:
    """The command line of rosdep: install, check and keys with upstream's options; init and update."""
    parser = argparse.ArgumentParser(
        prog='rosdep', description='Install and check the dependencies of ROS packages. Keys resolve '
        'to installed ROS packages, Python modules, or the pinned ros-<name> wheels (pip).')
    commands = parser.add_subparsers(title='commands', dest='command',
                                     metavar='{install,check,keys,init,update}')

    def with_selection(name: str, help_text: str) -> argparse.ArgumentParser:
        command = commands.add_parser(name, help=help_text, description=help_text)
        command.add_argument('names', nargs='*', metavar='path_or_package',
                             help='folders to search for packages (with --from-paths), else package names')
        command.add_argument('--from-paths', '--from-path', dest='from_paths', action='store_true',
                             help='the arguments are folders, searched recursively for package.xml files')
        command.add_argument('-i', '--ignore-src', '--ignore-packages-from-source', dest='ignore_src',
                             action='store_true',
                             help='do not resolve keys that are packages found in the given folders')
        command.add_argument('--rosdistro', help='accepted for compatibility; keys resolve for this '
                             'environment\'s distribution')
        command.add_argument('-t', '--dependency-types', action='append', choices=list(DEPENDENCY_TYPES),
                             default=[], help='only these dependency types (repeatable; default: all)')
        command.add_argument('--skip-keys', nargs='+', action='extend', default=[], metavar='KEY',
                             help='keys to leave out')
        command.add_argument('--os', help='accepted for compatibility; ignored')
        command.add_argument('-q', '--quiet', action='store_true', help='print only errors')
        command.set_defaults(command_parser=command)
        return command

    install = with_selection('install', 'Install the dependencies of the given packages')
    install.add_argument('-y', '--default-yes', dest='yes', action='store_true',
                         help='install without asking')
    install.add_argument('-r', dest='robust', action='store_true',
                         help='continue installing the resolvable keys when some cannot be resolved')
    install.add_argument('-s', '--simulate', action='store_true',
                         help='print the installation commands instead of running them')
    with_selection('check', 'Check whether the dependencies of the given packages are installed')
    with_selection('keys', 'List the dependency keys of the given packages')
    commands.add_parser('init', help='Nothing to do here (kept so that scripts calling it still work)')
    commands.add_parser('update', help='Nothing to do here (kept so that scripts calling it still work)')
    return parser


def main(argv: list[str] | None = None) -> int:
    """The rosdep command: its exit code for argv (None: sys.argv), 130 at Ctrl-C."""
    try:
        return run(argv)
    except KeyboardInterrupt:
        return 130


def run(argv: list[str] | None) -> int:
    """Parse the command line, read the selected packages' keys and run the command; its exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    if args.command in ('init', 'update'):
        print(NOTHING_TO_SET_UP.format(verb=args.command))
        return 0
    if not args.names:
        args.command_parser.error('no packages given: use --from-paths <folder> ..., or package names')
    try:
        packages = (packages_in_paths(args.names) if args.from_paths
                    else installed_packages(args.names))
    except ManifestError as error:
        print(f'ERROR: {error}', file=sys.stderr)
        return 1
    _note_rosdistro(args.rosdistro)
    types = args.dependency_types or list(DEPENDENCY_TYPES)
    ignored = set(args.skip_keys)
    if args.ignore_src:
        ignored |= {package.name for package in packages}
    keys_by_package = {package.name: [key for key in dependency_keys(package, types) if key not in ignored]
                       for package in packages}
    if args.command == 'keys':
        for key in sorted({key for keys in keys_by_package.values() for key in keys}):
            print(key)
        return 0
    plan = make_plan(keys_by_package, Resolver(load_pins(default_requirements()), load_wheel_table()))
    if args.command == 'check':
        return check(plan)
    return install(plan, args)


def make_plan(keys_by_package: dict[str, list[str]], resolver: Resolver) -> Plan:
    """Resolve the keys of each package: the pip requirements to install and the keys that failed."""
    plan = Plan()
    resolved: dict[str, Resolution] = {}
    for package, keys in keys_by_package.items():
        for key in keys:
            if key not in resolved:  # each key is looked up once, however many packages name it
                resolved[key] = resolver.resolve(key)
            resolution = resolved[key]
            if resolution.error:
                plan.errors.append(f'{package}: {resolution.error}')
            elif resolution.pip and resolution.pip not in plan.pip:
                plan.pip.append(resolution.pip)
    return plan


def print_errors(plan: Plan) -> None:
    """Print the keys that did not resolve to stderr, under upstream rosdep's heading."""
    print('ERROR: the following packages/stacks could not have their rosdep keys resolved\n'
          'to system dependencies:', file=sys.stderr)
    for line in plan.errors:
        print(line, file=sys.stderr)


def check(plan: Plan) -> int:
    """`rosdep check`: print what is missing as upstream does; exit code 0 when nothing is, else 1."""
    if plan.errors:
        print_errors(plan)
    if plan.pip:
        print('System dependencies have not been satisfied:')
        for requirement in plan.pip:
            print(f'pip\t{requirement}')
    if plan.errors or plan.pip:
        return 1
    print('All system dependencies have been satisfied')
    return 0


def pip_command(requirements: list[str]) -> list[str]:
    """Installs into the environment this rosdep runs in (the venv of env.sh)."""
    return [sys.executable, '-m', 'pip', 'install', *requirements]


def install(plan: Plan, args: argparse.Namespace) -> int:
    """`rosdep install`: run pip for the plan (or print its commands with -s); the exit code.

    1 when a key did not resolve (after installing the others with -r), pip failed or the user did
    not confirm; without -y confirmation is asked at a terminal only, else refused.
    """
    failed = 1 if plan.errors else 0
    if plan.errors:
        print_errors(plan)
        if not args.robust:
            return 1
        print('Continuing to install resolvable dependencies...', file=sys.stderr)
    if not plan.pip:
        if not args.quiet:
            print(SUCCESS)
        return failed
    if args.simulate:
        print('#[pip] Installation commands:')
        for requirement in plan.pip:
            print('  ' + shlex.join(pip_command([requirement])))
        return failed
    command = pip_command(plan.pip)
    if not args.yes and not _confirm(command):
        print('ERROR: not installing without confirmation: rerun with -y to let rosdep run pip',
              file=sys.stderr)
        return 1
    if not args.quiet:
        print(f'executing command [{shlex.join(command)}]')
    if subprocess.run(command, check=False).returncode != 0:
        print(f'ERROR: the following rosdeps failed to install\n  pip: command [{shlex.join(command)}] '
              'failed', file=sys.stderr)
        return 1
    if not args.quiet:
        print(SUCCESS)
    return failed


def _confirm(command: list[str]) -> bool:
    if not sys.stdin.isatty():
        return False
    answer = input(f'{shlex.join(command)}\nRun this command? [Y/n] ').strip().lower()
    return answer in ('', 'y', 'yes')


def _note_rosdistro(rosdistro: str | None) -> None:
    current = os.environ.get('ROS_DISTRO')
    if rosdistro and current and rosdistro != current:
        print(f'WARNING: given --rosdistro {rosdistro} but this environment is ROS 2 {current}: '
              f'resolving for {current}.', file=sys.stderr)


if __name__ == '__main__':
    sys.exit(main())
