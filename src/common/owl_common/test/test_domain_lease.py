"""Domain leases: exclusive on the machine, and a process's next lease moves on to another domain."""

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
