"""Section 3.4: a package of one's own, created by ros2 pkg create and built by colcon."""

from __future__ import annotations

from pathlib import Path

from owl_cli.check import workspace as ws
from owl_cli.check.catalogue import Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    Session,
    workspace,
)

SECTION = Section()


@SECTION.check(
    'test_package',
    '3.4',
    'test_package',
    'ros2 pkg create test_package --build-type ament_python: the package layout colcon builds',
)
def check_test_package(s: Session) -> None:
    """Check test_package: in the workspace, ament_python, the layout ros2 pkg create gives, installed."""
    from ament_index_python.packages import PackageNotFoundError, get_package_prefix

    found = ws.packages(workspace()).get('test_package')
    if not s.add(
        Criterion(
            'the workspace has a package named test_package (package.xml)',
            found is not None,
            'in src/: ros2 pkg create test_package --build-type ament_python',
        )
    ):
        return
    assert found is not None
    s.add(
        Criterion(
            'its build type is ament_python (package.xml: <build_type>ament_python</build_type>)',
            found.build_type == 'ament_python',
            f'it is an {found.build_type} package: without --build-type ament_python, ros2 pkg create '
            'makes a CMake package; delete it and create it again with --build-type ament_python',
            found.build_type,
        )
    )
    missing = ws.package_layout_problems(found.path, 'test_package')
    s.add(
        Criterion(
            'it has the layout ros2 pkg create gives: package.xml, setup.py, setup.cfg, '
            'resource/test_package, '
            'test_package/__init__.py',
            not missing,
            'create the package with ros2 pkg create rather than by hand, or add what is missing',
            '; '.join(missing),
        )
    )
    try:
        prefix = Path(get_package_prefix('test_package')).resolve()
    except PackageNotFoundError:
        prefix = None
    s.add(
        Criterion(
            'colcon build installs it: ros2 pkg list lists test_package',
            prefix is not None and workspace().resolve() in prefix.parents,
            'run colcon build --symlink-install in the workspace root, then source install/setup.bash',
            str(prefix or 'not installed'),
        )
    )
