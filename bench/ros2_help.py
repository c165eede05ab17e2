"""How long `ros2 -h` (and a command's and a verb's help) takes, now that commands and verbs are
found through Python entry points.

Prints the median and max wall time in milliseconds of each, over --runs runs, and the ratio of the
median to the baseline's, measured in the same invocation: `python -c pass` in the same environment
(the interpreter's own start, with the workspace's sys.path; what `ros2` adds on top is its own
work). Target: `ros2 -h` within 0.25 s of the baseline on a quiet machine.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

CASES = {
    'baseline: python -c pass': [sys.executable, '-c', 'pass'],
    'ros2 -h': ['ros2', '-h'],
    'ros2 topic -h': ['ros2', 'topic', '-h'],
    'ros2 topic list -h': ['ros2', 'topic', 'list', '-h'],
    'ros2 pkg -h': ['ros2', 'pkg', '-h'],
}


def wall_times(argv: list[str], runs: int) -> list[float]:
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        result = subprocess.run(argv, capture_output=True, text=True, timeout=60, check=False)
        times.append(time.perf_counter() - started)
        if result.returncode != 0:
            raise SystemExit(f'{" ".join(argv)} exited with {result.returncode}: {result.stderr.strip()}')
    return times


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--runs', type=int, default=15, help='runs of each command (default 15)')
    args = parser.parse_args()
    if args.runs < 1:
        parser.error('--runs must be at least 1')
    if shutil.which('ros2') is None:
        print('ros2_help: ros2 is not on PATH (source env.sh first)', file=sys.stderr)
        return 1
    # One warm-up each: the first run after a build pays for the file system cache and .pyc files.
    for argv in CASES.values():
        wall_times(argv, 1)
    # Interleaved, so that load from other processes on the machine hits every case alike.
    samples: dict[str, list[float]] = {name: [] for name in CASES}
    for _ in range(args.runs):
        for name, argv in CASES.items():
            samples[name] += wall_times(argv, 1)
    baseline = statistics.median(samples['baseline: python -c pass'])
    print(f'{"command":<28}{"median ms":>10}{"max ms":>9}{"ratio":>8}{"added ms":>10}   '
          f'({args.runs} runs each, {os.cpu_count()} cores)')
    for name, times in samples.items():
        median = statistics.median(times)
        print(f'{name:<28}{median * 1000:>10.0f}{max(times) * 1000:>9.0f}{median / baseline:>8.2f}'
              f'{(median - baseline) * 1000:>10.0f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
