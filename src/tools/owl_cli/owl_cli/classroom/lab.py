"""The students' lab: this checkout as every account of the class can run it.

The teacher's checkout may sit where other accounts cannot enter, and its venv's Python often
does (pyenv or uv under /root). So the class server copies the checkout's files (those git tracks
or would track: nothing it ignores, so no venv or build) into the lab folder (STATE/lab unless
--lab says where; classes may share one) and runs the project's own
bootstrap there on the system's python3 (the same minor version carries the same wheels). Students
read and run it; only root writes it. Every student's terminal and front door start from its
env.sh, as `source env.sh` does in a checkout. It is made again when a file of the checkout
changed (one digest over the names and contents).
"""

from __future__ import annotations

import fcntl
import os
import shutil
import subprocess
from pathlib import Path

from owl_cli.classroom import ClassError, files_digest, run_step, stamp_matches, write_stamp

# What `source env.sh` (and the workspace's setup it sources) adds to a shell: the lab's bootstrap
# runs without it, or the teacher's checkout would leak into the lab. The rest (a proxy, a
# certificate authority, a package index) the bootstrap needs as the teacher's shell has it.
ENV_SH_PREFIXES = ('ROS_', 'AMENT_', 'COLCON_', 'OWL_', 'RMW_', 'FASTRTPS_', 'RCUTILS_', '_ROS_')
ENV_SH_NAMES = {'VIRTUAL_ENV', 'VIRTUAL_ENV_PROMPT', 'PYTHONPATH', 'CMAKE_PREFIX_PATH', 'LD_LIBRARY_PATH',
                'PKG_CONFIG_PATH', 'OPENBLAS_NUM_THREADS', 'PS1'}
SYSTEM_PATH = '/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin'
MANIFEST = '.owl-lab-files'


def checkout_files(root: Path) -> list[str]:
    """The checkout's files, relative to root, sorted: git's tracked and untracked, none it ignores."""
    try:
        listed = subprocess.run(['git', '-C', str(root), 'ls-files', '-z', '--cached', '--others',
                                 '--exclude-standard'], capture_output=True, check=False)
    except FileNotFoundError:
        raise ClassError('git is missing: the lab copies what git tracks in this checkout') from None
    if listed.returncode != 0:
        raise ClassError(f'{root} is not a git checkout: the lab copies the files git tracks '
                         "('git clone' Owl Kit Lab)")
    names = {name for name in listed.stdout.decode().split('\0') if name}
    return sorted(name for name in names if (root / name).is_file())  # tracked but deleted: not copied


def copy_files(root: Path, lab: Path, names: list[str]) -> None:
    """Bring lab's copy to names as they are under root; files an earlier copy made and root lost go."""
    manifest = lab / MANIFEST
    earlier = set(manifest.read_text().splitlines()) if manifest.is_file() else set()
    for name in sorted(earlier - set(names)):
        (lab / name).unlink(missing_ok=True)
    for name in names:
        target = lab / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / name, target)
    manifest.write_text(''.join(f'{name}\n' for name in names))


def bootstrap_environment(environ: dict[str, str], python: str) -> dict[str, str]:
    """The environment the lab's bootstrap runs in: environ without env.sh's additions, on python."""
    kept = {name: value for name, value in environ.items()
            if name not in ENV_SH_NAMES and not name.startswith(ENV_SH_PREFIXES)}
    return {**kept, 'PATH': SYSTEM_PATH, 'PYTHON': python}


def ensure_lab(lab: Path, root: Path, python: str) -> Path:
    """lab, copied from the checkout at root and bootstrapped on python when either changed.

    Several class servers may share one lab: one builds it while the others wait.
    """
    names = checkout_files(root)
    digest = files_digest(root, names) + f' {python}\n'
    lab.mkdir(mode=0o755, parents=True, exist_ok=True)
    with open(lab / '.owl-lab.lock', 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if stamp_matches(lab, digest):
            return lab
        print("owl class: building the students' lab (this checkout, bootstrapped on "
              f'{python}; a few minutes the first time) ...', flush=True)
        write_stamp(lab, None)  # a lab half made is made again at the next start
        copy_files(root, lab, names)
        run_step(['bash', str(lab / 'scripts' / 'bootstrap.sh')], "building the lab (its copy's make setup)",
                 environment=bootstrap_environment(dict(os.environ), python))
        run_step(['chmod', '-R', 'a+rX,go-w', str(lab)], "opening the lab to the class's accounts")
        write_stamp(lab, digest)
    return lab
