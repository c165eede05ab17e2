"""The text of every file `ros2 pkg create` writes. Pure functions of the package's settings."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

# Upstream's test dependencies for Python packages; the ament_* ones are our packages of the same
# names in src/compat (ruff stands in for flake8 and pydocstyle).
PYTHON_TEST_DEPENDS = ('ament_copyright', 'ament_flake8', 'ament_pep257', 'python3-pytest')
# ament_lint_auto/ament_lint_common would need a CMake linter set this environment lacks (see the
# README), so CMake packages' tests check the manifest and the node with what is installed.
CMAKE_TEST_DEPENDS = ('ament_cmake_test', 'python3-catkin-pkg')


@dataclass
class PackageSettings:
    """What the user asked `ros2 pkg create` for, already checked."""

    name: str
    build_type: str = 'ament_cmake'
    package_format: int = 3
    description: str = 'TODO: Package description'
    license: str = 'TODO: License declaration'
    maintainer_name: str = 'user'
    maintainer_email: str = 'user@todo.todo'
    dependencies: list[str] = field(default_factory=list)
    node_name: str | None = None
    library_name: str | None = None

    @property
    def buildtool_depends(self) -> list[str]:
        """package.xml's buildtool_depend: ament_cmake_ros for a CMake library, else ament_cmake or none."""
        if self.build_type != 'ament_cmake':
            return []
        return ['ament_cmake_ros'] if self.library_name else ['ament_cmake']

    @property
    def test_depends(self) -> list[str]:
        """The test_depend entries: PYTHON_TEST_DEPENDS or CMAKE_TEST_DEPENDS, by build type."""
        return list(PYTHON_TEST_DEPENDS if self.build_type == 'ament_python' else CMAKE_TEST_DEPENDS)

    @property
    def maintainer(self) -> str:
        """'name <email>', as package.xml and the summary name the maintainer."""
        return f'{self.maintainer_name} <{self.maintainer_email}>'

    @property
    def class_name(self) -> str:
        """The C++ class of the library: my_lib -> MyLib."""
        return ''.join(part.capitalize() for part in (self.library_name or '').split('_'))


def package_xml(p: PackageSettings) -> str:
    """package.xml, in the format asked for, with the text values XML-escaped."""
    lines = [
        '<?xml version="1.0"?>',
        f'<?xml-model href="http://download.ros.org/schema/package_format{p.package_format}.xsd" '
        'schematypens="http://www.w3.org/2001/XMLSchema"?>',
        f'<package format="{p.package_format}">',
        f'  <name>{p.name}</name>',
        '  <version>0.0.0</version>',
        f'  <description>{escape(p.description)}</description>',
        f'  <maintainer email={quoteattr(p.maintainer_email)}>{escape(p.maintainer_name)}</maintainer>',
        f'  <license>{escape(p.license)}</license>',
        '',
    ]
    for tag, names in (('buildtool_depend', p.buildtool_depends), ('depend', p.dependencies),
                       ('test_depend', p.test_depends)):
        if names:
            lines += [f'  <{tag}>{name}</{tag}>' for name in names] + ['']
    lines += [
        '  <export>',
        f'    <build_type>{p.build_type}</build_type>',
        '  </export>',
        '</package>',
    ]
    return '\n'.join(lines) + '\n'


# ---------------------------------------------------------------------------- ament_python

def setup_py(p: PackageSettings) -> str:
    """setup.py of an ament_python package, with a console script for the node if one was asked for."""
    scripts = [f'{p.node_name} = {p.name}.{p.node_name}:main'] if p.node_name else []
    script_lines = ''.join(f'            {s!r}\n' for s in scripts)
    return (
        'from setuptools import find_packages, setup\n'
        '\n'
        f'package_name = {p.name!r}\n'
        '\n'
        'setup(\n'
        '    name=package_name,\n'
        "    version='0.0.0',\n"
        "    packages=find_packages(exclude=['test']),\n"
        '    data_files=[\n'
        "        ('share/ament_index/resource_index/packages',\n"
        "            ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        '    ],\n'
        "    install_requires=['setuptools'],\n"
        '    zip_safe=True,\n'
        f'    maintainer={p.maintainer_name!r},\n'
        f'    maintainer_email={p.maintainer_email!r},\n'
        f'    description={p.description!r},\n'
        f'    license={p.license!r},\n'
        "    tests_require=['pytest'],\n"
        '    entry_points={\n'
        "        'console_scripts': [\n"
        f'{script_lines}'
        '        ],\n'
        '    },\n'
        ')\n'
    )


def setup_cfg(p: PackageSettings) -> str:
    """setup.cfg, which installs the scripts in lib/<package>."""
    # Scripts go to lib/<package>, where `ros2 run` looks for them.
    return (f'[develop]\nscript_dir=$base/lib/{p.name}\n'
            f'[install]\ninstall_scripts=$base/lib/{p.name}\n')


def python_node(p: PackageSettings) -> str:
    """The Python node: a main() that prints a greeting."""
    return (
        'def main():\n'
        f"    print('Hi from {p.name}.')\n"
        '\n'
        '\n'
        "if __name__ == '__main__':\n"
        '    main()\n'
    )


def _linter_test(module: str, function: str, markers: tuple[str, ...], body: str,
                 comment: str = '') -> str:
    """A test/test_<linter>.py as upstream writes it: import the linter's entry point, mark, call."""
    decorators = ''.join(f'@pytest.mark.{marker}\n' for marker in markers)
    return (
        f'from {module}.main import {function}\n'
        'import pytest\n'
        '\n'
        '\n'
        f'{comment}'
        f'{decorators}'
        f'{body}'
    )


def copyright_test(p: PackageSettings) -> str:
    """test/test_copyright.py: ament_copyright on the package, skipped until the files carry headers."""
    return _linter_test(
        'ament_copyright', 'main', (
            "skip(reason='No copyright header has been placed in the generated source file.')",
            'copyright', 'linter'),
        'def test_copyright():\n'
        "    rc = main(argv=['.', 'test'])\n"
        "    assert rc == 0, 'Found errors'\n",
        comment='# Delete the skip mark once every source file starts with a copyright and license header\n')


def flake8_test(p: PackageSettings) -> str:
    """test/test_flake8.py: ament_flake8 on the package, failing with the list of problems."""
    return _linter_test(
        'ament_flake8', 'main_with_errors', ('flake8', 'linter'),
        'def test_flake8():\n'
        '    rc, errors = main_with_errors(argv=[])\n'
        '    assert rc == 0, \\\n'
        "        'Found %d code style errors / warnings:\\n' % len(errors) + \\\n"
        "        '\\n'.join(errors)\n")


def pep257_test(p: PackageSettings) -> str:
    """test/test_pep257.py: ament_pep257 on the package's code and tests."""
    return _linter_test(
        'ament_pep257', 'main', ('linter', 'pep257'),
        'def test_pep257():\n'
        "    rc = main(argv=['.', 'test'])\n"
        "    assert rc == 0, 'Found code style errors / warnings'\n")


# ---------------------------------------------------------------------------- ament_cmake

def cmakelists(p: PackageSettings) -> str:
    """CMakeLists.txt of an ament_cmake package: its dependencies, library, node and tests.

    The tests check that package.xml parses and, with a node, that the node starts and greets.
    """
    out = [
        'cmake_minimum_required(VERSION 3.8)',
        f'project({p.name})',
        '',
        'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")',
        '  add_compile_options(-Wall -Wextra -Wpedantic)',
        'endif()',
        '',
        '# find dependencies',
        'find_package(ament_cmake REQUIRED)',
        # ament_cmake_ros builds libraries shared unless BUILD_SHARED_LIBS says otherwise.
        *(['find_package(ament_cmake_ros REQUIRED)'] if p.library_name else []),
    ]
    out += [f'find_package({dep} REQUIRED)' for dep in p.dependencies] or [
        '# further dependencies: find_package(<dependency> REQUIRED) for each one']
    targets = ' '.join(f'${{{dep}_TARGETS}}' for dep in p.dependencies)
    include_dirs = ('  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n'
                    '  $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)')
    lib = p.library_name
    if lib:
        out += [
            '',
            f'add_library({lib} src/{lib}.cpp)',
            f'add_library({p.name}::{lib} ALIAS {lib})',
            f'target_compile_features({lib} PUBLIC c_std_99 cxx_std_17)',
            f'target_include_directories({lib} PUBLIC\n{include_dirs}',
            *([f'target_link_libraries({lib} PUBLIC {targets})'] if targets else []),
            '# exports the symbols marked in visibility_control.h while the library is built',
            f'target_compile_definitions({lib} PRIVATE "{p.name.upper()}_BUILDING_LIBRARY")',
            '',
            'install(DIRECTORY include/ DESTINATION include/${PROJECT_NAME})',
            f'install(TARGETS {lib}',
            '  EXPORT export_${PROJECT_NAME}',
            '  ARCHIVE DESTINATION lib',
            '  LIBRARY DESTINATION lib',
            '  RUNTIME DESTINATION bin)',
        ]
    node = p.node_name
    if node:
        out += [
            '',
            f'add_executable({node} src/{node}.cpp)',
            f'target_include_directories({node} PUBLIC\n{include_dirs}',
            f'target_compile_features({node} PUBLIC c_std_99 cxx_std_17)',
        ]
        linked = ' '.join(filter(None, [lib, targets]))
        if linked:
            out.append(f'target_link_libraries({node} {linked})')
        out.append(f'install(TARGETS {node} DESTINATION lib/${{PROJECT_NAME}})')
    out += [
        '',
        'if(BUILD_TESTING)',
        '  # Run by `colcon test`: the manifest must parse as a valid package.xml'
        + (', and the node must start and greet.' if node else '.'),
        '  find_package(ament_cmake_test REQUIRED)',
        '  find_package(Python3 REQUIRED COMPONENTS Interpreter)',
        '  ament_add_test(package_xml GENERATE_RESULT_FOR_RETURN_CODE_ZERO',
        '    COMMAND "${Python3_EXECUTABLE}" -c',
        '      "import sys; from catkin_pkg.package import parse_package; parse_package(sys.argv[1])"',
        '      "${CMAKE_CURRENT_SOURCE_DIR}")',
    ]
    if node:
        out += [
            f'  ament_add_test({node}_runs GENERATE_RESULT_FOR_RETURN_CODE_ZERO',
            f'    COMMAND "$<TARGET_FILE:{node}>")',
            f'  set_tests_properties({node}_runs PROPERTIES',
            f'    PASS_REGULAR_EXPRESSION "hello world {p.name} package")',
        ]
    out += ['endif()', '']
    if lib:
        out += [
            'ament_export_include_directories("include/${PROJECT_NAME}")',
            f'ament_export_libraries({lib})',
            'ament_export_targets(export_${PROJECT_NAME})',
            *([f'ament_export_dependencies({" ".join(p.dependencies)})'] if p.dependencies else []),
            '',
        ]
    out.append('ament_package()')
    return '\n'.join(out) + '\n'


def cpp_node(p: PackageSettings) -> str:
    """The C++ node: a main() that prints `hello world <package> package`."""
    include = f'#include "{p.name}/{p.library_name}.hpp"\n' if p.library_name else ''
    return (
        '#include <cstdio>\n'
        f'{include}'
        '\n'
        'int main(int argc, char ** argv)\n'
        '{\n'
        '  (void) argc;\n'
        '  (void) argv;\n'
        '\n'
        f'  printf("hello world {p.name} package\\n");\n'
        '  return 0;\n'
        '}\n'
    )


def cpp_header(p: PackageSettings) -> str:
    """include/<package>/<library>.hpp: the library's class, its constructor and destructor exported."""
    guard = f'{p.name}__{p.library_name}_HPP_'.upper()
    return (
        f'#ifndef {guard}\n'
        f'#define {guard}\n'
        '\n'
        f'#include "{p.name}/visibility_control.h"\n'
        '\n'
        f'namespace {p.name}\n'
        '{\n'
        '\n'
        f'class {p.class_name}\n'
        '{\n'
        'public:\n'
        f'  {p.name.upper()}_PUBLIC {p.class_name}();\n'
        f'  {p.name.upper()}_PUBLIC virtual ~{p.class_name}();\n'
        '};\n'
        '\n'
        f'}}  // namespace {p.name}\n'
        '\n'
        f'#endif  // {guard}\n'
    )


def cpp_library(p: PackageSettings) -> str:
    """The library's source, src/<library>.cpp: the class's default constructor and destructor."""
    return (
        f'#include "{p.name}/{p.library_name}.hpp"\n'
        '\n'
        f'namespace {p.name}\n'
        '{\n'
        '\n'
        f'{p.class_name}::{p.class_name}() = default;\n'
        '\n'
        f'{p.class_name}::~{p.class_name}() = default;\n'
        '\n'
        f'}}  // namespace {p.name}\n'
    )


def visibility_control(p: PackageSettings) -> str:
    """include/<package>/visibility_control.h: the <PACKAGE>_PUBLIC export macro."""
    macro = p.name.upper()
    return (
        f'#ifndef {macro}__VISIBILITY_CONTROL_H_\n'
        f'#define {macro}__VISIBILITY_CONTROL_H_\n'
        '\n'
        '// <PACKAGE>_PUBLIC marks what the shared library exports: dllexport/dllimport on\n'
        '// Windows, default visibility with GCC and Clang.\n'
        '#if defined _WIN32 || defined __CYGWIN__\n'
        f'  #ifdef {macro}_BUILDING_LIBRARY\n'
        f'    #define {macro}_PUBLIC __declspec(dllexport)\n'
        '  #else\n'
        f'    #define {macro}_PUBLIC __declspec(dllimport)\n'
        '  #endif\n'
        '#else\n'
        f'  #define {macro}_PUBLIC __attribute__ ((visibility("default")))\n'
        '#endif\n'
        '\n'
        f'#endif  // {macro}__VISIBILITY_CONTROL_H_\n'
    )


# ---------------------------------------------------------------------------- LICENSE

# The SPDX identifiers ament knows (the list upstream prints), in its order.
LICENSES = ('Apache-2.0', 'BSL-1.0', 'BSD-2.0', 'BSD-3-Clause', 'BSD-2-Clause', 'MIT', 'MIT-0',
            'GPL-3.0-only', 'LGPL-3.0-only')
# Full texts that Debian ships with every system (base-files).
COMMON_LICENSES_DIR = '/usr/share/common-licenses'
COMMON_LICENSE_FILES = {'Apache-2.0': 'Apache-2.0', 'GPL-3.0-only': 'GPL-3', 'LGPL-3.0-only': 'LGPL-3'}


def license_file(p: PackageSettings) -> str:
    """The LICENSE file: the SPDX identifier and a link to the text.

    The full text follows when the system has a copy in /usr/share/common-licenses.
    """
    text = (f'SPDX-License-Identifier: {p.license}\n'
            f'Full text: https://spdx.org/licenses/{p.license}.html\n')
    system_copy = os.path.join(COMMON_LICENSES_DIR, COMMON_LICENSE_FILES.get(p.license, ''))
    if p.license in COMMON_LICENSE_FILES and os.path.isfile(system_copy):
        with open(system_copy, encoding='utf-8') as f:
            text += '\n' + f.read()
    return text
