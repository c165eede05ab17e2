"""The class's Unix accounts: one per student and one for the teacher, each with a private home.

JupyterHub logs them in through PAM and starts each one's server as that account, so a student's
files and processes are the operating system's to keep apart. An account of ours is in the group
STUDENTS or TEACHERS; any other existing account of the same name is refused, never changed.
Running the class list again sets the passwords it gives and keeps every home as it is.
"""

from __future__ import annotations

import grp
import os
import pwd
import subprocess
import time

from owl_cli.classroom import run_step

STUDENTS = 'owl-students'
TEACHERS = 'owl-teachers'


def member_of(name: str, group: str) -> bool:
    """Whether the existing account name is in group (as its own group or as an extra one)."""
    try:
        info = grp.getgrnam(group)
        account = pwd.getpwnam(name)
    except KeyError:
        return False
    return name in info.gr_mem or account.pw_gid == info.gr_gid


def exists(name: str) -> bool:
    """Whether an account of that name exists on this machine."""
    try:
        pwd.getpwnam(name)
    except KeyError:
        return False
    return True


def conflict(name: str, group: str) -> str | None:
    """Why name cannot be this class's account of group, or None when it is ours or free."""
    if not exists(name) or member_of(name, group):
        return None
    return f"an account named '{name}' already exists on this machine and is not one of the class's"


def ensure_group(group: str) -> None:
    """Make the system group unless it exists."""
    try:
        grp.getgrnam(group)
    except KeyError:
        run_step(['groupadd', '--system', group], 'groupadd')


def ensure_account(name: str, password: str, group: str) -> bool:
    """Make name's account in group with a home only it can read, or keep it; set its password.

    True when the account was made now.
    """
    made = not exists(name)
    if made:
        run_step(['useradd', '--create-home', '--shell', '/bin/bash', '--groups', group, name], 'useradd')
    os.chmod(pwd.getpwnam(name).pw_dir, 0o700)  # Debian's useradd makes homes readable by all
    run_step(['chpasswd'], 'chpasswd', stdin=f'{name}:{password}\n')
    return made


def stop_processes(names: list[str], grace: float = 5.0) -> None:
    """End every process of these accounts: SIGTERM, and SIGKILL to what is left after grace seconds."""
    users = ','.join(name for name in names if exists(name))
    if not users:
        return
    subprocess.run(['pkill', '--signal', 'TERM', '--uid', users], check=False)
    deadline = time.monotonic() + grace
    while subprocess.run(['pgrep', '--uid', users], capture_output=True, check=False).returncode == 0:
        if time.monotonic() > deadline:
            subprocess.run(['pkill', '--signal', 'KILL', '--uid', users], check=False)
            return
        time.sleep(0.1)
