"""A student's or a third party's colcon workspace in a temporary folder, driven through bash."""

import subprocess
from pathlib import Path


def shell(workspace: Path, command: str, env: dict[str, str] | None = None,
          timeout: float = 300) -> subprocess.CompletedProcess:
    """`command` in bash in the workspace, with its install/local_setup.bash sourced once it exists."""
    setup = workspace / 'install' / 'local_setup.bash'
    script = (f'source {setup} && ' if setup.exists() else '') + command
    return subprocess.run(['bash', '-c', script], capture_output=True, text=True, cwd=workspace,
                          env=env, timeout=timeout, check=False)
