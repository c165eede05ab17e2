"""src/ is laid out by role: each group's packages import only the groups below them.

The groups and their rules are docs/architecture.md's picture; each group's README says the same in
words. The compat packages stand in for ROS 2 itself, so every other package sees them only
through names that upstream Jazzy has: that is what lets the course, the kit and the tools build
on a normal ROS 2 install with `src/compat/` left out (the README's recipe).
"""

from __future__ import annotations

import ast
import io
import re
import sys
import tokenize
import xml.etree.ElementTree as ET
from collections.abc import Iterable
from functools import cache
from graphlib import CycleError, TopologicalSorter
from pathlib import Path

import pytest

pytestmark = pytest.mark.no_processes

SRC = Path(__file__).resolve().parents[1] / 'src'

# group -> the groups of ours its packages may import (compat is ROS 2: see UPSTREAM_NAMES).
MAY_IMPORT = {
    'common': {'common'},
    'compat': {'compat', 'common'},
    'web': {'web', 'common'},
    'kit': {'kit', 'web', 'common'},
    'course': {'course'},
    'tools': {'tools', 'kit', 'web', 'common'},
}
# Our stand-ins for upstream tools (rqt, rosdep): left out on a real install, like compat, so they
# may use compat's own additions (the type lookup with reasons, FieldError).
STAND_INS = {'rqt_web', 'owl_rosdep'}
# The kit's description is data that the simulator and the tools share, and the windows folder is
# loaded by the venv's start-up hook before any workspace: the standard library only.
STDLIB_ONLY = {'olive_kit', 'owl_windows'}

# What the packages outside compat import from compat's packages: all of it is upstream Jazzy's
# public surface (ros2/launch, ros2/launch_ros, ros2/rosidl_runtime_py, ros-perception/vision_opencv,
# ros/ros_tutorials on their jazzy branches). A new name goes here once upstream is seen to have it.
UPSTREAM_NAMES = {
    'cv_bridge': {'CvBridge', 'CvBridgeError'},
    'launch': {'LaunchContext', 'LaunchDescription'},
    'launch.actions': {'DeclareLaunchArgument', 'IncludeLaunchDescription', 'LogInfo', 'OpaqueFunction'},
    'launch.launch_description_entity': {'LaunchDescriptionEntity'},
    'launch.launch_description_sources': {'PythonLaunchDescriptionSource'},
    'launch.substitutions': {'LaunchConfiguration', 'PathJoinSubstitution', 'ThisLaunchFileDir'},
    'launch_ros.actions': {'Node'},
    'rosidl_runtime_py.convert': {'message_to_ordereddict'},
    'rosidl_runtime_py.utilities': {'get_service'},
    'turtlesim.msg': {'Pose'},
    'turtlesim.srv': {'Kill', 'SetPen', 'Spawn', 'TeleportAbsolute', 'TeleportRelative'},
}


@cache
def packages() -> dict[str, Path]:
    """ROS package name -> its folder, for every package.xml under src/."""
    found = {}
    for manifest in SRC.rglob('package.xml'):
        name = ET.parse(manifest).getroot().findtext('name')
        assert name, manifest
        found[name] = manifest.parent
    return found


def group_of(package: str) -> str:
    return packages()[package].relative_to(SRC).parts[0]


@cache
def module_owners() -> dict[str, str]:
    """Top-level Python module -> the package that installs it.

    Interface packages generate a module named after themselves.
    """
    owners = {name: name for name in packages()}
    for name, folder in packages().items():
        for child in folder.iterdir():
            if (child / '__init__.py').is_file():
                owners[child.name] = name
    return owners


def imports(package: str) -> list[tuple[Path, str, set[str]]]:
    """(file, module, names) of every absolute import in the package's code (its unit tests aside)."""
    found = []
    folder = packages()[package]
    for path in sorted(folder.rglob('*.py')):
        if 'test' in path.relative_to(folder).parts or path.name == 'setup.py':
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                found.append((path, node.module, {alias.name for alias in node.names}))
            elif isinstance(node, ast.Import):
                found += [(path, alias.name, set()) for alias in node.names]
    return found


def is_interface_package(package: str) -> bool:
    """Whether a package is messages and services only (olive_interfaces), which the tools may import.

    `owl check` calls the course's services with the course's own types, so the tools may import these,
    never the course's nodes.
    """
    folder = packages()[package]
    return (folder / 'CMakeLists.txt').is_file() and any((folder / kind).is_dir() for kind in ('msg', 'srv'))


def ours(module: str) -> str | None:
    return module_owners().get(module.split('.')[0])


def test_every_package_sits_in_a_group_with_a_readme_of_its_rules():
    for name, folder in packages().items():
        parts = folder.relative_to(SRC).parts
        assert len(parts) == 2, f'{name}: {folder} is not src/<group>/<package>'
        assert parts[0] in MAY_IMPORT, f'{name}: {folder} is not src/<group>/<package>'
    for group in MAY_IMPORT:
        readme = SRC / group / 'README.md'
        assert readme.is_file(), f'{readme} is missing'
        assert 'may import' in readme.read_text().lower(), f'{readme} does not say what may be imported'


@pytest.mark.parametrize('package', sorted(packages()))
def test_imports_point_down_the_groups(package):
    group = group_of(package)
    wrong = []
    for path, module, names in imports(package):
        owner = ours(module)
        if package in STDLIB_ONLY and module.split('.')[0] not in sys.stdlib_module_names:
            wrong.append(f'{path}: {module} (this package imports the standard library only)')
        if owner is None or owner == package:
            continue
        owner_group = group_of(owner)
        if owner_group == 'compat' and group != 'compat' and package not in STAND_INS:
            extra = names - UPSTREAM_NAMES.get(module, set()) if names else {module}
            if extra:
                wrong.append(f'{path}: {module} {sorted(extra)} (not upstream Jazzy names)')
        elif owner_group != 'compat' and owner_group not in MAY_IMPORT[group] and not (
                group == 'tools' and is_interface_package(owner)):
            wrong.append(f'{path}: {module} ({owner} is in {owner_group}/, which {group}/ may not import)')
        elif group == 'tools' and owner_group == 'kit' and owner not in STDLIB_ONLY:
            wrong.append(f'{path}: {module} (the tools know the kit by its description, not its nodes)')
    assert not wrong, '\n'.join(wrong)


@pytest.mark.parametrize('package', sorted(packages()))
def test_declared_dependencies_point_down_the_groups(package):
    root = ET.parse(packages()[package] / 'package.xml').getroot()
    group = group_of(package)
    for tag in ('depend', 'exec_depend', 'build_depend'):
        for element in root.iter(tag):
            target = element.text or ''
            if target in packages() and group_of(target) != 'compat':
                assert group_of(target) in MAY_IMPORT[group], f'{package} {tag}s on {target}'


def test_no_package_imports_itself_back():
    graph = {name: {ours(module) for _, module, _ in imports(name)} - {None, name} for name in packages()}
    try:
        order = list(TopologicalSorter(graph).static_order())
    except CycleError as cycle:
        pytest.fail(f'packages import each other in a cycle: {cycle.args[1]}')
    assert set(order) == set(packages())


def python_modules() -> dict[str, Path]:
    """Dotted name -> file of every module of our Python packages under src/ (tests aside)."""
    found = {}
    for path in SRC.rglob('*.py'):
        parts = path.relative_to(SRC).parts
        if 'test' in parts or path.name == 'setup.py':
            continue
        for depth in range(len(parts) - 1):
            folder = SRC.joinpath(*parts[:depth + 1])
            if (folder / '__init__.py').is_file() and not (folder.parent / '__init__.py').is_file():
                name = '.'.join(parts[depth:])[:-3].removesuffix('.__init__')
                found[name] = path
                break
    return found


def runtime_imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """Our modules that `name` imports, as it loads or in its functions (TYPE_CHECKING blocks aside).

    `from package import submodule` counts as an import of the submodule, as a package's own
    __init__ is loaded before any of its modules anyway.
    """
    def known(dotted: str) -> str | None:
        while dotted and dotted not in modules:
            dotted = dotted.rpartition('.')[0]
        return dotted or None

    def loaded(node: ast.AST) -> list[ast.Import | ast.ImportFrom]:
        """The import statements that can run: anywhere but in an `if TYPE_CHECKING:` block."""
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            return [node]
        if isinstance(node, ast.If) and 'TYPE_CHECKING' in ast.unparse(node.test):
            return loaded_all(node.orelse)
        return loaded_all(ast.iter_child_nodes(node))

    def loaded_all(nodes: Iterable[ast.AST]) -> list[ast.Import | ast.ImportFrom]:
        return [statement for node in nodes for statement in loaded(node)]

    found: set[str | None] = set()
    for statement in loaded(ast.parse(path.read_text(), str(path))):
        if isinstance(statement, ast.Import):
            found |= {known(alias.name) for alias in statement.names}
        else:
            base = statement.module or ''
            if statement.level:
                package = name.split('.') if path.name == '__init__.py' else name.split('.')[:-1]
                package = package[:len(package) - statement.level + 1]
                base = '.'.join([*package, *([base] if base else [])])
            submodules = {f'{base}.{alias.name}' for alias in statement.names} & modules.keys()
            found |= submodules if len(submodules) == len(statement.names) else {known(base)}
    return {module for module in found if module is not None and module != name}


def test_no_module_imports_itself_back():
    # Imports inside functions count too: a lazy import that closes a cycle is still a cycle.
    modules = python_modules()
    assert len(modules) > 300
    graph = {name: runtime_imports(name, path, modules) for name, path in modules.items()}
    try:
        list(TopologicalSorter(graph).static_order())
    except CycleError as cycle:
        pytest.fail(f'modules import each other in a cycle: {cycle.args[1]}')



# owl check's plug-ins, one per course section: what two sections share lives in owl_cli.check
# (kit_helpers, session, ...), so a section's module stands alone and can move to another package.
EXERCISES = 'owl_cli.check.exercises.'


def exercise_cross_imports(modules: dict[str, Path]) -> dict[str, list[str]]:
    """Exercise module -> the other exercise modules it imports, for those that import any."""
    exercises = {name for name in modules if name.startswith(EXERCISES)}
    found = {name: sorted(runtime_imports(name, modules[name], modules) & exercises) for name in exercises}
    return {name: others for name, others in found.items() if others}


def test_no_exercise_module_imports_another():
    modules = python_modules()
    assert len([name for name in modules if name.startswith(EXERCISES)]) >= 12
    assert exercise_cross_imports(modules) == {}


def test_an_exercise_module_importing_another_is_seen(tmp_path):
    first, second = tmp_path / 'section_1.py', tmp_path / 'section_2.py'
    first.write_text('X = 1\n')
    second.write_text('def check():\n    from owl_cli.check.exercises.section_1 import X\n')
    modules = {f'{EXERCISES}section_1': first, f'{EXERCISES}section_2': second}
    assert exercise_cross_imports(modules) == {f'{EXERCISES}section_2': [f'{EXERCISES}section_1']}

# A page's own address, the front door's /<mount>/, and a proxy's /user/NAME/proxy/PORT/ are all the
# same page: it must name its files, API and WebSocket relative to itself. What an absolute reference
# looks like in our pages' HTML, CSS and JavaScript (a root-relative path or this machine's address).
ABSOLUTE_REFERENCE = re.compile(
    r'''(?:href|src)=["']/|url\(\s*["']?/|from\s+["']/|import\(\s*["']/|fetch\(\s*[`"']/|["'`]/(?:api|ws|lib|owl|static)/'''
    r'''|"(?:three|uplot|[\w-]+)"\s*:\s*"/|location\.(?:host|origin)\b(?!\s*===\s*before)|https?://127\.|localhost:\d''')


def test_every_page_refers_to_its_files_api_and_websocket_relatively():
    files = [path for path in SRC.rglob('*') if path.suffix in ('.html', '.js', '.css')
             and any('static' in part for part in path.relative_to(SRC).parts)]
    assert len(files) > 10
    found = [f'{path.relative_to(SRC)}:{number}: {line.strip()}'
             for path in files for number, line in enumerate(path.read_text().splitlines(), 1)
             if ABSOLUTE_REFERENCE.search(line)]
    assert found == []


# Where the ROS environment's variables may still be read as raw text: the one reader, and two that
# need the text as typed (ros2 doctor reports and judges it; the bridge's socket name carries it).
ROS_ENV_READERS = {
    'common/owl_common/owl_common/ros_env.py',
    'compat/ros2doctor/ros2doctor/api/network.py',
    'common/owl_humble/owl_humble/launcher.py',
}
ROS_ENV_READ = re.compile(r"""(environ|env)(\.get\(|\[)['"](ROS_DOMAIN_ID|ROS_AUTOMATIC_DISCOVERY_RANGE|"""
                          r"""ROS_STATIC_PEERS)['"](?!\]\s*=[^=])""")  # a read, not `environ[...] = ...`


def product_modules() -> Iterable[tuple[str, str]]:
    """(path under src/, text) of every Python module of ours outside the course and the tests."""
    for path in sorted(SRC.rglob('*.py')):
        relative = path.relative_to(SRC).as_posix()
        if not relative.startswith('course/') and '/test/' not in relative:
            yield relative, path.read_text()


def test_the_ros_environment_is_read_in_one_place():
    readers = {relative for relative, text in product_modules() if ROS_ENV_READ.search(text)}
    assert readers <= ROS_ENV_READERS, readers - ROS_ENV_READERS  # use owl_common.ros_env instead
    bounds = {relative for relative, text in product_modules() if re.search(r'\b232\b', text)}
    assert bounds == {'common/owl_common/owl_common/ros_env.py'}, bounds  # MAX_DOMAIN_ID's one home


ARCHITECTURE = SRC.parent / 'docs' / 'architecture.md'


def architecture_packages(text: str) -> dict[str, set[str]]:
    """Group -> the packages docs/architecture.md lists under its '### group/' heading.

    A package is a bullet's leading backticked names, before its colon: "- `a`, `b` (how): what".
    """
    listed: dict[str, set[str]] = {}
    group = None
    for line in text.splitlines():
        heading = re.fullmatch(r'### (\w+)/', line)
        if heading:
            group = heading.group(1)
            listed[group] = set()
        elif line.startswith('## '):
            group = None
        elif group and line.startswith('- '):
            listed[group] |= set(re.findall(r'`(\w+)`', line[2:].split(':', 1)[0]))
    return listed


def test_the_architecture_page_lists_every_package_in_its_group():
    on_disk = {group: {folder.name for folder in (SRC / group).iterdir()
                       if folder.is_dir() and not folder.name.startswith(('_', '.'))}
               for group in MAY_IMPORT}
    assert architecture_packages(ARCHITECTURE.read_text()) == on_disk


def test_a_package_missing_from_the_architecture_page_is_seen():
    page = ('## The packages\n\n### kit/\n\n- `olive_kit`: data\n- `a`, `b` (both): c `not_this`\n\n'
            '## Outside\n- `x`: y\n')
    assert architecture_packages(page) == {'kit': {'olive_kit', 'a', 'b'}}


# The kit's topic names and the pages' ports have one home each: olive_kit.description (topic(),
# goal_topic(), IMU_TOPIC, ROBOT_VIEW_PORT, ...) and owl_web.pages (the front door's port).
# Written as a literal anywhere else outside the course's packages and the tests (which state the
# contract independently, so that a wrong description fails them), they are a second home. Except:
FACT_HOMES = {
    'src/kit/olive_kit/olive_kit/description.py',
    'src/web/owl_web/owl_web/pages.py',  # FRONT_DOOR_PORT: the web layer sits below the kit
    # Runs at the interpreter's start, before any workspace is importable: its hint names the topics.
    'src/tools/owl_venv_hooks/owl_gui_hook.py',
    # A Humble module on the wire, in common/, which sits below the kit and cannot import it.
    'src/common/owl_humble/owl_humble/twin.py',
}
KIT_TOPIC = re.compile(r'/olive/(imu/|servo/|camera/|\{|\$\{)(?!<)')
PAGE_PORTS = {8042, 8090, 8091, 8092, 8093}


def fact_literals(path: Path, text: str) -> list[int]:
    """Lines of a Python module, page script or page where a kit topic name or a page's port is written.

    In Python, strings (docstrings too) and numbers count; a comment may name one.
    """
    if path.suffix != '.py':
        return [n for n, line in enumerate(text.splitlines(), 1) if KIT_TOPIC.search(line)]
    found = []
    for token in tokenize.generate_tokens(io.StringIO(text).readline):
        if token.type in (tokenize.STRING, getattr(tokenize, 'FSTRING_MIDDLE', tokenize.STRING)):
            if KIT_TOPIC.search(token.string):
                found.append(token.start[0])
        elif token.type == tokenize.NUMBER and token.string.isdigit() and int(token.string) in PAGE_PORTS:
            found.append(token.start[0])
    return found


def test_kit_topic_names_and_page_ports_are_written_in_one_place():
    root = SRC.parent
    found = []
    for base in ('src', 'scripts', 'bench'):
        for path in sorted((root / base).rglob('*')):
            relative = path.relative_to(root)
            elsewhere = bool({'test', 'node_modules'} & set(relative.parts))
            elsewhere = elsewhere or relative.parts[:2] == ('src', 'course')
            if path.suffix not in ('.py', '.js', '.html') or relative.as_posix() in FACT_HOMES or elsewhere:
                continue
            found += [f'{relative}:{line}' for line in fact_literals(path, path.read_text())]
    assert found == []  # use olive_kit.description (topic(), goal_topic(), ...) or owl_web.pages


def test_a_second_home_of_a_kit_fact_is_seen():
    code = ("'''Goals on /olive/servo/pan/goal/position.'''\n"
            "X = f'/olive/servo/{s}/joint'  # /olive/imu/\nPORT = 8091\n")
    assert fact_literals(Path('a.py'), code) == [1, 2, 3]
    assert fact_literals(Path('a.js'), 'const a = 1;\nb.title = `/olive/servo/${servo}/goal`;\n') == [2]
