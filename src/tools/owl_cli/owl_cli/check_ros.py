"""The part of `owl check` that drives ROS: one exercise's check in a private ROS domain.

Runs as its own process (`python -m owl_cli.check_ros EXERCISE`), started by `owl check` in a
shell that has sourced the student's workspace, so `ros2 run` finds the student's executables and
this process imports the student's interface types. The check itself is the exercise's plug-in
(owl_cli/exercises/), run on a check_session.Session that stops everything it started.
"""

from __future__ import annotations

import os
import signal
import sys

# Discovery stays on this machine whatever the student's shell says (set before rclpy starts).
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from owl_cli import check_catalogue as catalogue
from owl_cli.check_session import Failed, Session


def run(exercise_id: str) -> int:
    """Run the exercise's check on a new Session and close it, also at SIGTERM; the exit code, 0.

    The criteria go to stdout as the check decides them; a Failed criterion ends the check early.
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
        check(session)
    except Failed:
        pass
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
    if len(sys.argv) != 2 or sys.argv[1] not in ids:
        print(f'usage: python -m owl_cli.check_ros {{{",".join(ids)}}}', file=sys.stderr)
        return 2
    return run(sys.argv[1])


if __name__ == '__main__':
    sys.exit(main())
