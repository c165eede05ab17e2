"""`ros2 pkg create`: check the request, then write the package the way upstream does.

check_settings() turns command line values into PackageSettings or raises CreateError with one
line for the user; plan() lists the folders and files (pure); write_package() creates them,
printing upstream's `creating ...` lines.
"""

from __future__ import annotations

import difflib
import keyword
import os
import re
import shutil
from collections.abc import Callable
from dataclasses import dataclass

from ros2pkg import templates
from ros2pkg.templates import LICENSES, PackageSettings

BUILD_TYPES = ('ament_cmake', 'ament_python')
# Build types upstream offers that this environment cannot build.
UNSUPPORTED_BUILD_TYPES = ('cmake', 'ament_cargo')
DEFAULT_LICENSE = 'TODO: License declaration'

# REP 144: lowercase letters, digits and underscores, starting with a letter, no '__'.
PACKAGE_NAME = re.compile(r'[a-z][a-z0-9_]*')
IDENTIFIER = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
DEPENDENCY_KEY = re.compile(r'[A-Za-z0-9][A-Za-z0-9_.+-]*')
# What catkin_pkg accepts in package.xml (name@host.tld), so generated manifests validate.
EMAIL = re.compile(r'[A-Za-z0-9_%+-]+(\.[A-Za-z0-9_%+-]+)*@[A-Za-z0-9%-]+(\.[A-Za-z0-9%-]+)*\.[A-Za-z]{2,}')


class CreateError(Exception):
    """A request `ros2 pkg create` refuses; str() is the one line for the user."""

    def __init__(self, message: str, exit_code: int = 1):
        super().__init__(message)
        self.exit_code = exit_code


def closest(word: str, choices: tuple[str, ...] | list[str]) -> str | None:
    """The choice the user most likely meant (ignoring case and '-' vs '_'), if any is close."""
    normalized = {choice.lower().replace('-', '_'): choice for choice in choices}
    key = word.lower().replace('-', '_')
    if key in normalized:
        return normalized[key]
    extensions = [choice for norm, choice in normalized.items() if norm.startswith(key)]
    if len(extensions) == 1:
        return extensions[0]
    matches = difflib.get_close_matches(key, list(normalized), n=1, cutoff=0.6)
    return normalized[matches[0]] if matches else None


def check_build_type(build_type: str) -> str:
    """The build type if this environment can build it, else CreateError with exit code 2.

    The error suggests the closest known build type, as argparse's choices would not.
    """
    if build_type in BUILD_TYPES:
        return build_type
    choices = ', '.join(f"'{b}'" for b in BUILD_TYPES)
    if build_type in UNSUPPORTED_BUILD_TYPES:
        raise CreateError(f"build type '{build_type}' is not supported here (choose from {choices})", 2)
    guess = closest(build_type, BUILD_TYPES)
    hint = f"did you mean '{guess}'?" if guess else f'choose from {choices}'
    raise CreateError(f"unknown build type '{build_type}', {hint}", 2)


def suggested_package_name(name: str) -> str:
    """A REP 144 name close to what the user typed: 'My-Package' -> 'my_package'."""
    words = re.findall(r'[a-z0-9]+', name.lower())
    suggestion = '_'.join(words)
    return suggestion if PACKAGE_NAME.fullmatch(suggestion) else ''


def check_package_name(name: str) -> None:
    """Refuse a name that breaks REP 144 with CreateError, suggesting a valid name close to it."""
    if PACKAGE_NAME.fullmatch(name) and '__' not in name:
        return
    suggestion = suggested_package_name(name)
    hint = f", did you mean '{suggestion}'?" if suggestion else ''
    raise CreateError(
        f"invalid package name '{name}': use lowercase letters, digits and single underscores, "
        f'starting with a letter (REP 144){hint}')


def check_identifier(what: str, name: str) -> None:
    """Refuse a node or library name that is not a Python identifier (or is a keyword) with CreateError."""
    if not IDENTIFIER.fullmatch(name) or keyword.iskeyword(name):
        raise CreateError(
            f"invalid {what} '{name}': use letters, digits and underscores, not starting with a digit")


def check_license(license_name: str) -> bool:
    """True for a license ament knows (a LICENSE file is written); False for free text.

    A near miss of a known identifier ('apache-2.0', 'MIT License') is refused rather than
    written into package.xml as an unknown license.
    """
    if license_name in LICENSES:
        return True
    guess = closest(license_name, LICENSES)
    if guess is None and license_name != DEFAULT_LICENSE:
        words = set(re.findall(r'[a-z0-9.]+', license_name.lower()))
        guess = next((known for known in LICENSES if known.lower() in words), None)
    if guess is not None:
        raise CreateError(f"unknown license '{license_name}', did you mean '{guess}'? "
                          "(`--license '?'` lists the supported licenses)")
    return False


def check_settings(name: str, build_type: str, dependencies: list[str], description: str,
                   license_name: str, maintainer_name: str, maintainer_email: str | None,
                   node_name: str | None, library_name: str | None, package_format: int,
                   destination: str, warn: Callable[[str], None]) -> PackageSettings:
    """Validate every value of a `ros2 pkg create` request; raise CreateError on the first bad one."""
    build_type = check_build_type(build_type)
    check_package_name(name)
    if build_type == 'ament_python' and name == 'test':
        raise CreateError("Aborted since 'ament_python' packages can't be named 'test'. "
                          'Please choose a different package name.')
    for dependency in dependencies:
        if not DEPENDENCY_KEY.fullmatch(dependency):
            raise CreateError(f"invalid dependency '{dependency}': expected a package name or rosdep key")
    if not maintainer_name.strip():
        raise CreateError('the maintainer name must not be empty')
    if maintainer_email is not None and not EMAIL.fullmatch(maintainer_email):
        raise CreateError(f"invalid maintainer email '{maintainer_email}': expected name@host.domain")
    if not description.strip():
        raise CreateError('the description must not be empty')
    if not license_name.strip():
        raise CreateError("the license must not be empty (`--license '?'` lists the supported licenses)")
    if node_name is not None:
        check_identifier('node name', node_name)
    if library_name is not None:
        check_identifier('library name', library_name)
        if node_name == library_name:
            node_name = f'{node_name}_node'
            warn('[WARNING] node name can not be equal to the library name')
            warn(f'[WARNING] renaming node to {node_name}')
    check_license(license_name)
    if os.path.exists(destination) and not os.path.isdir(destination):
        raise CreateError(f'the destination is not a directory: {destination}')
    package_path = os.path.join(destination, name)
    if os.path.exists(package_path):
        raise CreateError(f'Aborted! The directory already exists: {package_path}. Either remove the '
                          'directory or choose a different destination directory or package name')
    return PackageSettings(
        name=name, build_type=build_type, package_format=package_format, description=description,
        license=license_name, maintainer_name=maintainer_name,
        maintainer_email=maintainer_email or default_email(maintainer_name),
        dependencies=list(dependencies), node_name=node_name, library_name=library_name)


def default_email(maintainer_name: str) -> str:
    """Upstream's fallback when neither --maintainer-email nor `git config user.email` gives one."""
    local_part = re.sub(r'[^A-Za-z0-9_%+-]+', '_', maintainer_name).strip('_') or 'user'
    return f'{local_part}@todo.todo'


@dataclass(frozen=True)
class Step:
    """One thing create does: print a note, make a folder, or write a file (silently if quiet)."""

    kind: str  # 'note' | 'folder' | 'file'
    path: str = ''
    content: str = ''
    quiet: bool = False

    @property
    def message(self) -> str | None:
        """The line create prints for this step (`creating ...`), or None for a quiet step."""
        if self.quiet:
            return None
        return {'note': self.path, 'folder': f'creating folder {self.path}',
                'file': f'creating {self.path}'}[self.kind]


def plan(p: PackageSettings, destination: str) -> list[Step]:
    """Every folder and file of the new package, in upstream's order."""
    root = os.path.join(destination, p.name)
    steps = [Step('folder', root), Step('file', os.path.join(root, 'package.xml'), templates.package_xml(p))]
    if p.build_type == 'ament_python':
        source = os.path.join(root, p.name)
        test = os.path.join(root, 'test')
        steps += [
            Step('note', 'creating source folder'),
            Step('folder', source),
            Step('file', os.path.join(root, 'setup.py'), templates.setup_py(p)),
            Step('file', os.path.join(root, 'setup.cfg'), templates.setup_cfg(p)),
            Step('folder', os.path.join(root, 'resource')),
            Step('file', os.path.join(root, 'resource', p.name)),
            Step('file', os.path.join(source, '__init__.py')),
            Step('folder', test),
            Step('file', os.path.join(test, 'test_copyright.py'), templates.copyright_test(p)),
            Step('file', os.path.join(test, 'test_flake8.py'), templates.flake8_test(p)),
            Step('file', os.path.join(test, 'test_pep257.py'), templates.pep257_test(p)),
        ]
        if p.node_name:
            steps.append(Step('file', os.path.join(source, f'{p.node_name}.py'), templates.python_node(p)))
        if p.library_name:
            library = os.path.join(source, p.library_name)
            steps += [Step('folder', library), Step('file', os.path.join(library, '__init__.py'))]
    else:
        source = os.path.join(root, 'src')
        include = os.path.join(root, 'include', p.name)
        steps += [
            Step('note', 'creating source and include folder'),
            Step('folder', source),
            Step('folder', include),
            Step('file', os.path.join(root, 'CMakeLists.txt'), templates.cmakelists(p)),
        ]
        if p.node_name:
            steps.append(Step('file', os.path.join(source, f'{p.node_name}.cpp'), templates.cpp_node(p)))
        if p.library_name:
            steps += [
                Step('file', os.path.join(include, f'{p.library_name}.hpp'), templates.cpp_header(p)),
                Step('file', os.path.join(source, f'{p.library_name}.cpp'), templates.cpp_library(p)),
                Step('file', os.path.join(include, 'visibility_control.h'), templates.visibility_control(p)),
            ]
    if p.license in LICENSES:
        steps.append(Step('file', os.path.join(root, 'LICENSE'), templates.license_file(p), quiet=True))
    return steps


def summary(p: PackageSettings, destination: str) -> list[str]:
    """The lines upstream prints before it creates anything."""
    lines = [
        'going to create a new package',
        f'package name: {p.name}',
        f'destination directory: {os.path.abspath(destination)}',
        f'package format: {p.package_format}',
        'version: 0.0.0',
        f'description: {p.description}',
        f'maintainer: {[p.maintainer]}',
        f'licenses: {[p.license]}',
        f'build type: {p.build_type}',
        f'dependencies: {list(p.dependencies)}',
    ]
    if p.node_name:
        lines.append(f'node_name: {p.node_name}')
    if p.library_name:
        lines.append(f'library_name: {p.library_name}')
    return lines


def unknown_license_warning(license_name: str) -> str:
    """The warning printed after creating a package with a license ament does not know, and those it does."""
    return (f"\n[WARNING]: Unknown license '{license_name}'.  This has been set in the package.xml, "
            'but no LICENSE file has been created.\nIt is recommended to use one of the ament license '
            'identifiers:\n' + '\n'.join(LICENSES))


def write_package(steps: list[Step], say: Callable[[str], None]) -> None:
    """Carry out the plan; on an OS error remove what was made, then raise CreateError."""
    root = steps[0].path
    try:
        for step in steps:
            if step.message:
                say(step.message)
            if step.kind == 'folder':
                os.makedirs(step.path, exist_ok=True)
            elif step.kind == 'file':
                with open(step.path, 'w', encoding='utf-8') as f:
                    f.write(step.content)
    except OSError as error:
        shutil.rmtree(root, ignore_errors=True)
        raise CreateError(f'unable to create {error.filename or root}: {error.strerror}') from None
