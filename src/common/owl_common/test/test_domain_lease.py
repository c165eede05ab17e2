"""Domain leases: exclusive on the machine, and a process's next lease moves on to another domain."""

import itertools
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest
from owl_common import processes
from owl_common.processes import DomainLease


def test_a_lease_given_back_is_not_the_next_one_and_a_held_one_is_never_shared(tmp_path, monkeypatch):
    monkeypatch.setattr(processes, 'LEASE_DIR', tmp_path)
    first = DomainLease()
    first_domain = first.domain_id
    first.release()
    second = DomainLease()
    assert second.domain_id != first_domain  # what the first test left there may linger
    third = DomainLease()
    assert third.domain_id not in (first_domain, second.domain_id)
    second.release()
    third.release()


def test_a_domain_given_back_rests_while_another_is_free(tmp_path, monkeypatch):
    monkeypatch.setattr(processes, 'LEASE_DIR', tmp_path)
    monkeypatch.setattr(processes, 'DOMAIN_IDS', range(1, 3))
    monkeypatch.setattr(processes, 'LEASE_STARTS', itertools.repeat(0))  # every lease looks at 1 first
    leased = []
    for _ in range(3):
        lease = DomainLease()
        leased.append(lease.domain_id)
        lease.release()
    # 1 rests after its first lease, so 2; then both rest, and a free one is better than none
    assert leased == [1, 2, 1]


def test_every_account_leases_from_one_folder_and_a_lock_another_account_made_still_locks():
    if os.geteuid() != 0:
        pytest.skip('acting as another account needs root (CI runs as root)')
    folder = Path(tempfile.mkdtemp(prefix='owl-lease-test-'))
    try:
        folder.chmod(0o755)
        shutil.copy(processes.__file__, folder / 'lease.py')  # the module alone: the checkout may be closed
        leases = folder / 'leases'
        held = processes.try_lock_file(leases, [1])  # root's lock file, mode 0644
        assert held is not None
        assert leases.stat().st_mode & 0o7777 == 0o1777  # everyone may add a lease, as in /tmp
        as_nobody = subprocess.run(
            ['setpriv', '--reuid=nobody', '--regid=nogroup', '--clear-groups', '/usr/bin/python3', '-c',
             f'import sys; sys.path.insert(0, {str(folder)!r}); from pathlib import Path; import lease; '
             f'print(lease.try_lock_file(Path({str(leases)!r}), [1, 2])[0])'],
            capture_output=True, text=True, check=False)
        assert as_nobody.stdout.strip() == '2', as_nobody.stderr  # root's domain is held, not an error
        held[1].close()
    finally:
        shutil.rmtree(folder)
