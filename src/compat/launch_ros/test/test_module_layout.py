"""launch_ros's modules in upstream's shape: no import cycles, imports at the top, found by launch.

Read from the source with ast (nothing is imported), except the installed entry point.
"""

from __future__ import annotations

import ast
from importlib.metadata import entry_points
from pathlib import Path

PACKAGE_ROOT = Path(__file__).resolve().parents[1]
PACKAGE = PACKAGE_ROOT / 'launch_ros'
# Imports kept inside functions on purpose: module -> the modules it imports there.
LAZY = {'launch_ros.ros_adapters': {'rclpy', 'rclpy.executors', 'rclpy.signals'}}


def modules() -> dict[str, tuple[ast.Module, bool]]:
    """Dotted name -> (parsed source, whether it is a package's __init__)."""
    found = {}
    for path in sorted(PACKAGE.rglob('*.py')):
        parts = list(path.relative_to(PACKAGE_ROOT).with_suffix('').parts)
        is_package = parts[-1] == '__init__'
        found['.'.join(parts[:-1] if is_package else parts)] = (ast.parse(path.read_text()), is_package)
    return found


def is_type_checking(node: ast.stmt) -> bool:
    return isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == 'TYPE_CHECKING'


def top_level_imports(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    return [node for node in tree.body if isinstance(node, (ast.Import, ast.ImportFrom))]


def imported_names(node: ast.Import | ast.ImportFrom) -> list[str]:
    """Every dotted name an import statement may load (absolute imports only, as this package uses)."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    assert node.level == 0, ast.unparse(node)
    assert node.module, ast.unparse(node)
    return [node.module] + [f'{node.module}.{alias.name}' for alias in node.names]


def ancestors(name: str) -> list[str]:
    parts = name.split('.')
    return ['.'.join(parts[:i]) for i in range(1, len(parts))]


def import_graph() -> dict[str, set[str]]:
    """Module -> the modules of launch_ros that importing it runs first (parent packages included).

    A module's own parent packages are left out: they are being imported already when it runs.
    """
    found = modules()
    graph = {}
    for name, (tree, _) in found.items():
        edges = set()
        for node in top_level_imports(tree):
            for target in imported_names(node):
                edges |= {m for m in [*ancestors(target), target]
                          if m in found and m != name and m not in ancestors(name)}
        graph[name] = edges
    return graph


def test_no_module_imports_its_own_parent_package():
    for name, (tree, _) in modules().items():
        for node in tree.body:
            if isinstance(node, ast.ImportFrom):
                assert node.module not in ancestors(name), f'{name}: {ast.unparse(node)}'


def test_no_import_cycles_between_modules():
    graph = import_graph()
    done: set[str] = set()

    def visit(name: str, path: list[str]) -> None:
        if name in path:
            raise AssertionError('import cycle: ' + ' -> '.join([*path[path.index(name):], name]))
        if name in done:
            return
        for target in sorted(graph[name]):
            visit(target, [*path, name])
        done.add(name)

    assert len(graph) > 30
    for name in sorted(graph):
        visit(name, [])


def test_imports_are_at_the_top_except_the_listed_lazy_ones():
    lazy = {}
    for name, (tree, _) in modules().items():
        top = {id(node) for node in top_level_imports(tree)}
        top |= {id(node) for block in tree.body if is_type_checking(block) for node in ast.walk(block)}
        inner = {target for node in ast.walk(tree)
                 if isinstance(node, (ast.Import, ast.ImportFrom)) and id(node) not in top
                 for target in ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                                else [node.module])}
        if inner:
            lazy[name] = inner
    assert lazy == LAZY


def defines_something(tree: ast.Module) -> bool:
    """Whether a module has a class, a function or a value of its own (__all__ aside)."""
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef, ast.AnnAssign)):
            return True
        if isinstance(node, ast.Assign) and ast.unparse(node.targets[0]) != '__all__':
            return True
    return False


def test_no_module_only_re_exports_another_ones_names():
    # Upstream keeps lifecycle_node_matchers only as the old path of events.matchers' function.
    for name, (tree, is_package) in modules().items():
        if not is_package and name != 'launch_ros.events.lifecycle.lifecycle_node_matchers':
            assert defines_something(tree), name


def test_setup_declares_the_frontend_extension_as_upstream_does():
    setup = ast.parse((PACKAGE_ROOT / 'setup.py').read_text())
    [call] = [node for node in ast.walk(setup) if isinstance(node, ast.Call)
              and getattr(node.func, 'id', None) == 'setup']
    [declared] = [keyword.value for keyword in call.keywords if keyword.arg == 'entry_points']
    assert ast.literal_eval(declared) == {'launch.frontend.launch_extension': ['launch_ros = launch_ros']}


def test_the_installed_package_is_in_the_frontend_extension_group():
    found = {point.name: point.value for point in entry_points(group='launch.frontend.launch_extension')}
    assert found.get('launch_ros') == 'launch_ros'
