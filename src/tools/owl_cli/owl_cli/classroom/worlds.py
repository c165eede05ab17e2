"""Each account's private ROS world on the class server, and its front door's port.

Every account of the class (the students and the teacher) has a ROS domain of its own, kept across
restarts in STATE/ros-domains.json, and its server starts with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST:
discovery never leaves the machine, and on the machine it meets only the nodes of the same domain.
So a student's `ros2 node list` shows their own nodes, the kit of one student is not the kit of
another, and two students' turtlesims are two turtles. What bounds it: DOMAIN_IDS (1-101, the
domains whose DDS ports stay below Linux's ephemeral range), so at most 101 accounts per machine;
and a student who sets ROS_DOMAIN_ID by hand joins another's world (domains separate, they do not
lock: on Kubernetes each pod's own network closes that too, docs/classroom.md).
"""

from __future__ import annotations

import json
from collections.abc import Collection, Iterable, Mapping
from pathlib import Path
from typing import IO

from owl_common import processes
from owl_common.processes import DOMAIN_IDS

from owl_cli.classroom import ClassError

RECORD = 'ros-domains.json'
# Each account's front door listens on 127.0.0.1 at this plus its domain: below the ports DDS
# takes (7400 and up), so one student's robot cannot hold another's front door.
FRONT_DOOR_PORT_BASE = 7000


def assign_domains(known: Mapping[str, int], names: list[str], taken: Collection[int] = ()) -> dict[str, int]:
    """The domain of each of names: the one known for it, else the lowest no one known holds nor taken.

    Names known but no longer listed keep their domains (a student taken off the list and put back
    finds their world as it was). ClassError when the domains run out.
    """
    assigned = {name: known[name] for name in names if name in known}
    used = set(known.values()) | set(taken)
    free = (domain for domain in DOMAIN_IDS if domain not in used)
    for name in names:
        if name not in assigned:
            domain = next(free, None)
            if domain is None:
                first, last = DOMAIN_IDS.start, DOMAIN_IDS.stop - 1
                raise ClassError(f'no ROS domain left for {name}: a class server holds at most '
                                 f'{len(DOMAIN_IDS)} accounts (domains {first}-{last})')
            assigned[name] = domain
    return assigned


def read_domains(state: Path) -> dict[str, int]:
    """The domains recorded in state (none before the first start)."""
    path = state / RECORD
    if not path.is_file():
        return {}
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError) as error:
        raise ClassError(f'cannot read {path}: {error}') from None
    if not isinstance(record, dict) or not all(
            isinstance(domain, int) and domain in DOMAIN_IDS for domain in record.values()):
        raise ClassError(f'{path} is not a record of ROS domains ({{"name": 1..101}}): remove it to start '
                         'over (every student gets a new domain)')
    return record


def record_domains(state: Path, known: Mapping[str, int], assigned: Mapping[str, int]) -> dict[str, int]:
    """Write known with assigned's entries into state's record; the whole record."""
    record = {**known, **assigned}
    (state / RECORD).write_text(json.dumps(record, indent=1, sort_keys=True) + '\n')
    return record


def front_door_port(domain: int) -> int:
    """The port of the front door of the account with that domain."""
    return FRONT_DOOR_PORT_BASE + domain


def held_domains() -> list[int]:
    """The domains some process on this machine holds now (a test run's, an `owl check`'s)."""
    handles, held = hold_domains(DOMAIN_IDS)
    for handle in handles:
        handle.close()
    return held


def hold_domains(domains: Iterable[int]) -> tuple[list[IO[str]], list[int]]:
    """Lock these domains as leases (held until the handles close), and the ones another process holds."""
    handles, shared = [], []
    for domain in domains:
        lock = processes.try_lock_file(processes.LEASE_DIR, [domain])
        if lock is None:
            shared.append(domain)
        else:
            handles.append(lock[1])
    return handles, shared
