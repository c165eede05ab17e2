"""`owl class`: a class server on JupyterHub, one Unix account per student (docs/classroom.md)."""

from __future__ import annotations

import subprocess
from collections.abc import Mapping
from pathlib import Path


class ClassError(RuntimeError):
    """Why the class server cannot start, in one line."""


def run_step(argv: list[str], what: str, stdin: str | None = None,
             environment: Mapping[str, str] | None = None) -> None:
    """Run one setup step quietly; ClassError naming what failed, with its output's last line."""
    done = subprocess.run(argv, input=stdin, capture_output=True, text=True, check=False, env=environment)
    if done.returncode != 0:
        lines = (done.stderr or done.stdout).strip().splitlines()
        raise ClassError(f"{what} failed: {lines[-1] if lines else f'exit code {done.returncode}'}")


def closed_parent(folder: Path) -> Path | None:
    """The first existing folder above folder that other accounts cannot pass through, if any."""
    for parent in reversed(folder.absolute().parents):
        if parent.is_dir() and not parent.stat().st_mode & 0o001:
            return parent
    return None
