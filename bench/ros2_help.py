"""How long `ros2 -h` (and a command's and a verb's help) takes, with commands found by entry points.

Commands and verbs are now found through Python entry points.

Prints the median and max wall time in milliseconds of each, over --runs runs, and the ratio of the
median to the baseline's, measured in the same invocation: `python -c pass` in the same environment
(the interpreter's own start, with the workspace's sys.path; what `ros2` adds on top is its own
work). With --before CHECKOUT, the same commands of another checkout's set-up (e.g. the main
branch's, before entry points) run interleaved with these, in their environment (its env.sh).
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


def checkout_env(checkout: str) -> dict[str, str]:
    """The environment that `source <checkout>/env.sh` makes."""
    result = subprocess.run(['bash', '-c', f'source {checkout}/env.sh >/dev/null 2>&1; env -0'],
                            capture_output=True, timeout=60, check=True)
    pairs = (item.partition('=') for item in result.stdout.decode().split('\0') if '=' in item)
    return {name: value for name, _, value in pairs}


def wall_times(argv: list[str], runs: int, env: dict[str, str] | None = None) -> list[float]:
    """Wall times (s) of `runs` runs of argv in env; a failed run exits the bench (SystemExit)."""
    times = []
    for _ in range(runs):
        started = time.perf_counter()
        result = subprocess.run(argv, capture_output=True, text=True, timeout=60, check=False, env=env)
        times.append(time.perf_counter() - started)
        if result.returncode != 0:
            raise SystemExit(f'{" ".join(argv)} exited with {result.returncode}: {result.stderr.strip()}')
    return times


def main() -> int:
    """Time every case --runs times, interleaved, and print the table; exit code 0, or 1 without ros2."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--runs', type=int, default=15, help='runs of each command (default 15)')
    parser.add_argument('--before', metavar='CHECKOUT',
                        help="also time another checkout's `ros2` (its env.sh sourced), e.g. /work/main")
    args = parser.parse_args()
    if args.runs < 1:
        parser.error('--runs must be at least 1')
    if shutil.which('ros2') is None:
        print('ros2_help: ros2 is not on PATH (source env.sh first)', file=sys.stderr)
        return 1
    cases: dict[str, tuple[list[str], dict[str, str] | None]] = {
        name: (argv, None) for name, argv in CASES.items()}
    if args.before:
        if not os.path.isfile(os.path.join(args.before, 'env.sh')):
            parser.error(f"--before: '{args.before}' has no env.sh")
        before_env = checkout_env(args.before)
        for name, argv in CASES.items():
            if name.startswith('ros2 '):
                cases[f'before: {name}'] = (argv, before_env)
    # One warm-up each: the first run after a build pays for the file system cache and .pyc files.
    for argv, env in cases.values():
        wall_times(argv, 1, env)
    # Interleaved, so that load from other processes on the machine hits every case alike.
    samples: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(args.runs):
        for name, (argv, env) in cases.items():
            samples[name] += wall_times(argv, 1, env)
    baseline = statistics.median(samples['baseline: python -c pass'])
    print(f'{"command":<36}{"median ms":>10}{"max ms":>9}{"ratio":>8}{"added ms":>10}   '
          f'({args.runs} runs each, {os.cpu_count()} cores)')
    for name, times in samples.items():
        median = statistics.median(times)
        print(f'{name:<36}{median * 1000:>10.0f}{max(times) * 1000:>9.0f}{median / baseline:>8.2f}'
              f'{(median - baseline) * 1000:>10.0f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
