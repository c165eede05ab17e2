"""The environment a fresh `source env.sh` leaves, for the tests of what env.sh sets."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def after_env_sh(names: tuple[str, ...], unset: tuple[str, ...] = (),
                 preset: dict[str, str] | None = None) -> dict[str, str]:
    """The values of names after `source env.sh` in a shell without unset and with preset ('' when unset)."""
    env = {name: value for name, value in os.environ.items() if name not in unset}
    env.update(preset or {})
    script = 'source ./env.sh >/dev/null && ' + ' && '.join(f'echo "{n}=${{{n}:-}}"' for n in names)
    done = subprocess.run([shutil.which('bash') or 'bash', '-c', script], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=60, check=True)
    return dict(line.split('=', 1) for line in done.stdout.splitlines())
