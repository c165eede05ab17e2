"""`owl class`: a class server on JupyterHub, one Unix account per student (docs/classroom.md)."""

from __future__ import annotations

import hashlib
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


# What a folder (the hub's venv, the proxy's, the students' lab) was made from, so a start makes it
# again only when that changed.
STAMP = '.owl-inputs.sha256'


def files_digest(root: Path, names: list[str]) -> str:
    """One SHA-256 over the files' names (relative to root) and contents."""
    digest = hashlib.sha256()
    for name in names:
        digest.update(name.encode() + b'\0')
        digest.update((root / name).read_bytes())
        digest.update(b'\0')
    return digest.hexdigest()


def stamp_matches(folder: Path, digest: str) -> bool:
    """Whether folder was made from what digest describes (its stamp says so)."""
    stamp = folder / STAMP
    return stamp.is_file() and stamp.read_text() == digest


def write_stamp(folder: Path, digest: str | None) -> None:
    """Record what folder was made from; None removes the record (a folder half made is made again)."""
    if digest is None:
        (folder / STAMP).unlink(missing_ok=True)
    else:
        (folder / STAMP).write_text(digest)
