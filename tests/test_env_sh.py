"""What a fresh `source env.sh` leaves in the shell's environment, and what it leaves to the user."""

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


def test_openblas_runs_one_thread_unless_the_user_chose_otherwise():
    names = ('OPENBLAS_NUM_THREADS',)
    assert after_env_sh(names, unset=names) == {'OPENBLAS_NUM_THREADS': '1'}
    assert after_env_sh(names, preset={'OPENBLAS_NUM_THREADS': '4'}) == {'OPENBLAS_NUM_THREADS': '4'}
