"""The class image's recipe (config/classroom/image.sh), run here into a folder, checked as another account.

What Docker would add around it (the base image, the user, the registry) cannot run here; the steps
that make the image's lab, servers' venv and servers' configuration do, in the lab the class tests
share (a checkout set up on the system's python3, as the image's is).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from class_harness import CHECKOUT, LAB
from gates import prerequisite_missing
from owl_cli.classroom.hub import SYSTEM_PYTHON
from owl_cli.classroom.lab import bootstrap_environment, ensure_lab

AS_NOBODY = ['setpriv', '--reuid=nobody', '--regid=nogroup', '--clear-groups']


@pytest.mark.class_lab  # it takes the students' lab as built for the run (conftest.py)
def test_the_image_recipe_gives_a_lab_and_servers_another_account_runs():
    if os.geteuid() != 0:
        prerequisite_missing('the image is built as root, and checked as another account')
    ensure_lab(LAB, CHECKOUT, SYSTEM_PYTHON)
    image = Path(tempfile.mkdtemp(prefix='owl-class-image-'))
    try:
        image.chmod(0o755)
        config, servers = image / 'etc' / 'jupyter', image / 'server'
        recipe = LAB / 'config' / 'classroom' / 'image.sh'
        built = subprocess.run(['bash', str(recipe), str(config), str(servers)], capture_output=True,
                               text=True, timeout=300, check=False,
                               env=bootstrap_environment(dict(os.environ), SYSTEM_PYTHON))
        assert built.returncode == 0, built.stdout + built.stderr
        assert f"its servers' venv {servers}" in built.stdout
        plain = {'PATH': '/usr/bin:/bin', 'HOME': '/tmp', 'LANG': 'C.UTF-8'}
        # A pod's terminal: the lab's env.sh, and the course's commands find the lab's packages.
        terminal = subprocess.run([*AS_NOBODY, 'bash', '--rcfile', str(config / 'owl-terminal.bashrc'), '-i',
                                   '-c', 'ros2 pkg prefix turtlesim'], capture_output=True, text=True,
                                  timeout=60, env=plain, check=False)
        assert terminal.stdout.strip().splitlines()[-1] == str(LAB / 'install' / 'turtlesim'), terminal
        server = subprocess.run([*AS_NOBODY, str(servers / 'bin' / 'jupyterhub-singleuser'), '--version'],
                                capture_output=True, text=True, timeout=60, env=plain, check=False)
        assert server.returncode == 0, server.stderr
        assert f'{LAB}/env.sh' in (config / 'jupyter_server_config.py').read_text()
    finally:
        shutil.rmtree(image)


def image_of(checkout: Path, python: Path, into: Path) -> subprocess.CompletedProcess:
    """`owl class image` for a checkout whose venv's Python is python."""
    (checkout / '.venv' / 'bin').mkdir(parents=True)
    (checkout / '.venv' / 'bin' / 'python').symlink_to(python)
    (checkout / 'env.sh').write_text('')
    return subprocess.run(['owl', 'class', 'image', '--config-dir', str(into / 'etc'), '--server-venv',
                           str(into / 'server')], capture_output=True, text=True, timeout=60, check=False,
                          env={**os.environ, 'OWL_ROOT': str(checkout)})


def test_a_checkout_others_cannot_run_is_one_line_and_nothing_is_made(tmp_path):
    private = tmp_path / 'root-only'  # as a Python under /root (pyenv, uv)
    private.mkdir(mode=0o700)
    python = private / 'python3'
    python.write_text('#!/bin/sh\n')
    python.chmod(0o755)
    done = image_of(tmp_path / 'one', python, tmp_path)
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [
        f"owl class: the checkout's Python {python} is not one every account can run: set it up on the "
        "system's ('PYTHON=/usr/bin/python3 make setup')"]
    tmp_path.chmod(0o700)  # pytest's own folders are closed to other accounts anyway
    done = image_of(tmp_path / 'two', Path(SYSTEM_PYTHON), tmp_path)
    assert done.returncode == 2
    [line] = done.stderr.strip().splitlines()
    assert line.endswith('is closed to other accounts: every student runs the lab inside'), line
    assert not (tmp_path / 'server').exists()
    assert not (tmp_path / 'etc').exists()
