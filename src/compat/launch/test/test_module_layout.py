"""The shape of the package: upstream's module paths, no import cycles, formats from entry points."""

import ast
from graphlib import CycleError, TopologicalSorter
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ('launch', 'launch_xml', 'launch_yaml')
# The imports that run inside a function, each because a top-level one would close a cycle.
LAZY_IMPORTS = {
    ('launch.utilities.normalize_to_list_of_substitutions_impl', 'launch.substitutions.text_substitution'),
    ('launch.launch_description', 'launch.actions.declare_launch_argument'),
}


def modules() -> dict[str, Path]:
    """Module name -> file, for every module of the three packages."""
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob('*.py')):
            parts = list(path.relative_to(ROOT).with_suffix('').parts)
            if parts[-1] == '__init__':
                parts.pop()
            found['.'.join(parts)] = path
    return found


def top_level_statements(body: list[ast.stmt]) -> list[ast.stmt]:
    """The statements run at import, `if TYPE_CHECKING:` blocks left out."""
    statements = []
    for statement in body:
        if isinstance(statement, ast.If):
            if not (isinstance(statement.test, ast.Name) and statement.test.id == 'TYPE_CHECKING'):
                statements += top_level_statements(statement.body)
            statements += top_level_statements(statement.orelse)
        elif isinstance(statement, ast.Try):
            statements += top_level_statements(statement.body)
        else:
            statements.append(statement)
    return statements


def imported(node: ast.Import | ast.ImportFrom, known: dict[str, Path]) -> set[str]:
    """The modules of ours an import statement names (`from package import module` names module)."""
    if isinstance(node, ast.Import):
        return {alias.name for alias in node.names} & set(known)
    assert node.level == 0, 'the package imports absolutely'
    names = {f'{node.module}.{alias.name}' for alias in node.names}
    return {name if name in known else str(node.module) for name in names} & set(known)


def with_packages(module: str) -> set[str]:
    """A module and the packages it is in, which Python imports first."""
    parts = module.split('.')
    return {'.'.join(parts[:i]) for i in range(1, len(parts) + 1)}


def test_top_level_imports_form_no_cycle():
    known = modules()
    graph = {}
    for name, path in known.items():
        graph[name] = set()
        for node in top_level_statements(ast.parse(path.read_text()).body):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                for target in imported(node, known):
                    # The packages the module itself is in are being imported already.
                    graph[name] |= (with_packages(target) & set(known)) - with_packages(name)
    try:
        list(TopologicalSorter(graph).static_order())
    except CycleError as cycle:
        pytest.fail(f'modules import each other in a cycle: {cycle.args[1]}')


def test_imports_inside_functions_are_the_known_lazy_ones():
    known = modules()
    lazy = set()
    for name, path in known.items():
        for function in ast.walk(ast.parse(path.read_text())):
            if isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lazy |= {(name, target) for node in ast.walk(function)
                         if isinstance(node, (ast.Import, ast.ImportFrom))
                         for target in imported(node, known)}
    assert lazy == LAZY_IMPORTS


def test_the_frontend_formats_are_the_entry_points_of_launch_xml_and_launch_yaml():
    import launch_xml
    import launch_yaml
    from launch.frontend import Parser

    assert Parser.load_parser_implementations() == {'xml': launch_xml.Parser, 'yaml': launch_yaml.Parser}
    assert Parser.get_available_extensions() == ['xml', 'yaml', 'yml']
