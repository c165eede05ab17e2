"""The part of `owl check` that drives ROS: one exercise's check in a private ROS domain.

Runs as its own process (`python -m owl_cli.check.ros [--wait] EXERCISE`), started by `owl check`
in a shell that has sourced the student's workspace, so `ros2 run` finds the student's executables and
this process imports the student's interface types. The check itself is the exercise's plug-in
(owl_cli/check/exercises/), run on a session.Session that stops everything it started.
"""

from __future__ import annotations

import os
import signal
import sys

# Discovery stays on this machine whatever the student's shell says (set before rclpy starts).
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from owl_cli.check import catalogue
from owl_cli.check.report import CHECK_DONE
from owl_cli.check.session import Failed, Session

WAIT = '--wait'


def run(exercise_id: str, wait: bool = False) -> int:
    """Run the exercise's check on a new Session and close it, also at SIGTERM; the exit code, 0.

    The criteria go to stdout as the check decides them, then CHECK_DONE before the clean-up; a
    Failed criterion ends the check early. With wait (owl check starts an exercise's process while
    the one before is checked) the imports and the Session (its domain, its probe node) are made
    first and the check begins at a line on stdin; end of input ends it unchecked.
    """
    check = catalogue.BY_ID[exercise_id].check
    assert check is not None
    session = Session()
    stop = {'signal': False}

    def on_term(signum: int, frame: object) -> None:
        # owl check's hard time limit: clean up (finally below) instead of leaving the nodes behind.
        stop['signal'] = True
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, on_term)
    try:
        if wait and not sys.stdin.readline():
            return 0  # owl check ended before this exercise's turn
        try:
            check(session)
        except Failed:
            pass
        print(CHECK_DONE, flush=True)
    except KeyboardInterrupt:
        if not stop['signal']:
            raise
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        session.close()
    return 0


def main() -> int:
    """The process's entry point: check the exercise named by the one argument; 2 for a bad one."""
    ids = [e.id for e in catalogue.CHECKABLE]
    args = sys.argv[1:]
    wait = args[:1] == [WAIT]
    if wait:
        args = args[1:]
    if len(args) != 1 or args[0] not in ids:
        print(f'usage: python -m owl_cli.check.ros [{WAIT}] {{{",".join(ids)}}}', file=sys.stderr)
        return 2
    return run(args[0], wait)


if __name__ == '__main__':
    sys.exit(main())
