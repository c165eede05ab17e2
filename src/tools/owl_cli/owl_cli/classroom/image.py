"""owl class image: make this checkout the single-user image of a class on Kubernetes (docs/classroom.md).

Run while the image is built (config/classroom/image.sh runs it after `make setup` on the image's
python3): the checkout is the students' lab as it is, so its Python must be one every account can
run. It adds what `owl class serve` gives each student's server on one machine, minus what each
pod has of its own: the servers' venv (JupyterLab, jupyterhub-singleuser, jupyter-server-proxy at
config/classroom/requirements.txt's pins), and the servers' configuration (terminals that source
the lab's env.sh, the launcher tile of the front door at port 8090, the pod's own).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from owl_cli.classroom import ClassError, closed_parent, hub, run_step

CONFIG_DIR = Path('/etc/jupyter')
SERVER_VENV = Path('/opt/owl-kit-lab-server')


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of `owl class image`."""
    parser.add_argument('--config-dir', type=Path, default=CONFIG_DIR,
                        help=f"the servers' Jupyter configuration folder (default {CONFIG_DIR})")
    parser.add_argument('--server-venv', type=Path, default=SERVER_VENV,
                        help=f"the servers' venv: JupyterLab, jupyterhub-singleuser (default {SERVER_VENV})")


def runnable_by_all(path: Path) -> bool:
    """Whether every account can reach and run path (a file others may read and execute)."""
    return closed_parent(path) is None and path.stat().st_mode & 0o005 == 0o005


def run(args: argparse.Namespace) -> int:
    """`owl class image`: exit code 0, or 2 with one line saying what is wrong."""
    try:
        lab = hub.project_root()
        python = (lab / '.venv' / 'bin' / 'python').resolve()
        if not python.is_file():
            raise ClassError(f"{lab} is not set up: run 'make setup' first")
        if not runnable_by_all(python):
            raise ClassError(f"the checkout's Python {python} is not one every account can run: set it up "
                             "on the system's ('PYTHON=/usr/bin/python3 make setup')")
        closed = closed_parent(lab / 'env.sh')
        if closed is not None:
            raise ClassError(f'{closed} is closed to other accounts: every student runs the lab inside')
        venv = hub.ensure_venv(args.server_venv)
        hub.write_server_config(args.config_dir, lab)
        run_step(['chmod', '-R', 'a+rX', str(lab)], "opening the lab to every account")
    except (ClassError, OSError) as error:
        print(f'owl class: {error}', file=sys.stderr)
        return 2
    print(f"owl class: the image's lab is {lab}; its servers' venv {venv} "
          f"(start them with {venv / 'bin' / 'jupyterhub-singleuser'}), their configuration in "
          f'{args.config_dir} (JUPYTER_CONFIG_PATH, unless it is /etc/jupyter)')
    return 0
