"""How long `owl check` takes per exercise on the reference solutions, against a 30 s budget each.

Runs `owl check --json` over the repository's own workspace (the course's reference solutions) and
prints each exercise's seconds, from the check's begin to its last criterion. The baseline, measured
in the same run, is the floor a kit check cannot go under: the whole simulated kit (IMU, pan, tilt,
camera) started, waited for in the graph and stopped, as a check's session does. The ratio says how
many kit starts a check costs; the seconds say whether it keeps the budget. Timing assertions live
here, not in the tests (a shared machine makes them flaky there).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from owl_cli.check.session import Session

ROOT = Path(__file__).resolve().parents[1]
BUDGET = 30.0  # s per check, the owl check issue's target


def kit_start_and_stop() -> float:
    """Seconds to start the simulated kit, see its four nodes in the graph, and stop it again."""
    start = time.monotonic()
    session = Session()
    try:
        session.kit('imu', 'pan', 'tilt', 'camera')
    finally:
        session.close()
    return time.monotonic() - start


def check_seconds(exercises: list[str]) -> dict[str, float]:
    """Each exercise's seconds in one `owl check --json` of the reference workspace; exits on a failure."""
    arguments = exercises or ['--all']
    with tempfile.TemporaryDirectory(prefix='owl-check-bench-') as state:  # not the user's latest results
        done = subprocess.run(['owl', 'check', *arguments, '--workspace', str(ROOT), '--json'],
                              capture_output=True, text=True, check=False,
                              env={**os.environ, 'XDG_STATE_HOME': state})
    try:
        report = json.loads(done.stdout)
    except json.JSONDecodeError:
        sys.exit(f'owl check gave no report (exit {done.returncode}): {done.stderr.strip()[-500:]}')
    failed = [e['exercise'] for e in report['exercises'] if not e['passed']]
    if failed:
        sys.exit(f'a reference solution failed its check, so its time says nothing: {", ".join(failed)}')
    return {e['exercise']: e['seconds'] for e in report['exercises']}


def main() -> None:
    """Measure the baseline, then the checks, and print both."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--exercises', nargs='*', default=[], metavar='ID',
                        help='exercise ids to check (default: every one the workspace has, as --all)')
    parser.add_argument('--kit-runs', type=int, default=3, help='kit starts for the baseline (median)')
    args = parser.parse_args()
    if args.kit_runs < 1:
        parser.error('--kit-runs must be at least 1')
    kit = statistics.median(kit_start_and_stop() for _ in range(args.kit_runs))
    seconds = check_seconds(args.exercises)
    width = max(len(name) for name in seconds)
    for name, taken in sorted(seconds.items(), key=lambda item: -item[1]):
        print(f'{name:<{width}}  {taken:6.1f} s{"   over the budget" if taken > BUDGET else ""}')
    median = statistics.median(seconds.values())
    within = sum(taken <= BUDGET for taken in seconds.values())
    print(f'baseline, the kit started and stopped: {kit:.1f} s (median of {args.kit_runs})')
    print(f'checks: {len(seconds)}, within {BUDGET:.0f} s: {within}, median {median:.1f} s, '
          f'slowest {max(seconds.values()):.1f} s; median check / kit start = {median / kit:.1f}')


if __name__ == '__main__':
    main()
