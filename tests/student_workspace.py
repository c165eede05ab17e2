"""A student's own colcon workspace next to Owl Kit Lab's: commands run in it, packages built in it.

Shared by tests/test_chapter4_walkthrough.py (packages written as the course says) and
tests/test_owl_check.py (the broken variants of tests/owl_check_variants/).
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path


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
