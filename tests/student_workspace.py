"""A student's own colcon workspace next to Owl Kit Lab's: commands run in it, packages built in it.

Shared by tests/test_chapter4_walkthrough.py (packages written as the course says),
tests/test_owl_check.py (the broken variants of tests/owl_check_variants/) and
tests/test_ros2cli_extensions.py (a third party's ros2 commands).
"""

from __future__ import annotations

import fcntl
import os
import shutil
import subprocess
from pathlib import Path

import pytest
from owl_cli.classroom import files_digest


def shell(
    workspace: Path, command: str, env: dict[str, str] | None = None, timeout: float = 300
) -> subprocess.CompletedProcess:
    """A bash command in the workspace, with its overlay sourced once it is built."""
    setup = workspace / 'install' / 'local_setup.bash'
    script = (f'source {setup} && ' if setup.exists() else '') + command
    return subprocess.run(
        ['bash', '-c', script],
        capture_output=True,
        text=True,
        cwd=workspace,
        env=env,
        timeout=timeout,
        check=False,
    )


def build_from(workspace: Path, packages: list[Path]) -> Path:
    """Copy the package folders into workspace/src and colcon build them; return the workspace."""
    (workspace / 'src').mkdir(parents=True, exist_ok=True)
    for package in packages:
        shutil.copytree(package, workspace / 'src' / package.name)
    build = shell(workspace, 'colcon build --symlink-install')
    assert build.returncode == 0, build.stdout + build.stderr
    return workspace


BUILT = '.built'  # in a shared workspace: written once its build succeeded


def packages_digest(packages: list[Path]) -> str:
    """A digest of the package folders' files: their paths (below the folders' common parent) and contents."""
    root = Path(os.path.commonpath(packages)).parent
    names = [str(path.relative_to(root)) for package in packages for path in sorted(package.rglob('*'))
             if path.is_file() and '__pycache__' not in path.parts]
    return files_digest(root, names)[:16]


def shared_build(tmp_path_factory: pytest.TempPathFactory, packages: list[Path]) -> Path:
    """A workspace of the package folders built once for the whole run, for tests that only read it.

    With pytest-xdist a module-scoped fixture is made once per worker, and the tests of a module spread
    over the workers: the same six packages were built three times in a run (12 s of CPU each).
    The workers of one run share their base folder's parent; the first to ask builds under a lock,
    the others wait for it and use its workspace. A build that failed is tried again by the next.
    """
    base = tmp_path_factory.getbasetemp()
    run_folder = base.parent if base.name.startswith('popen-gw') else base
    workspace = run_folder / 'shared-workspaces' / packages_digest(packages)
    workspace.parent.mkdir(parents=True, exist_ok=True)
    with open(workspace.with_suffix('.lock'), 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if not (workspace / BUILT).exists():
            shutil.rmtree(workspace, ignore_errors=True)
            build_from(workspace, packages)
            (workspace / BUILT).touch()
    return workspace
