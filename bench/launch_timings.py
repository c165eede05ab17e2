"""How long `ros2 launch` takes to start a process, to bring up turtlesim nodes and to stop on Ctrl-C.

Three times are measured: to start one process, to bring up the course's two turtlesim nodes, and to
bring everything down after Ctrl-C (SIGINT to launch).

Each measurement is repeated; prints median and max in milliseconds. The baseline, measured in the
same run, starts and stops the same two turtlesim nodes directly, without launch (what launch adds
is its own start-up, the launch file, and forwarding Ctrl-C).
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import statistics
import tempfile
import time
from pathlib import Path

from owl_common.processes import RosSandbox

ROOT = Path(__file__).resolve().parents[1]
STARTED = r'process started with pid \[(\d+)\]'
SLEEPER = '<launch><executable cmd="sleep 60"/></launch>\n'


def ms(seconds: float) -> float:
    """Seconds in milliseconds, the unit of the printed table."""
    return seconds * 1000.0


def launch_and_stop(sandbox: RosSandbox, argv: list[str], ready: str, count: int,
                    cwd: str | None = None) -> tuple[float, float]:
    """(seconds until `count` lines match `ready`, seconds from SIGINT to launch's exit)."""
    start = time.monotonic()
    process = sandbox.command(['ros2', 'launch', *argv], cwd=cwd)
    process.wait_for(ready, timeout=60, count=count)
    up = time.monotonic() - start
    stop = time.monotonic()
    os.kill(process.pid, signal.SIGINT)
    code = process.wait(30)
    down = time.monotonic() - stop
    if code != 0:
        raise SystemExit(f'ros2 launch exited with {code}:\n{process.output}')
    left = [pid for pid in map(int, re.findall(STARTED, process.output)) if Path(f'/proc/{pid}').exists()]
    if left:
        raise SystemExit(f'processes left running: {left}')
    return up, down


def start_and_stop_directly(sandbox: RosSandbox) -> tuple[float, float]:
    """The baseline: both turtlesim nodes of turtle.launch.py as plain processes, then SIGINT."""
    start = time.monotonic()
    nodes = [sandbox.run('turtlesim', 'turtlesim_node', '--ros-args', '-r', f'__node:={name}')
             for name in ('turtle1', 'turtle2')]
    for node in nodes:
        node.wait_for(r'Spawning turtle \[turtle1\]', timeout=60)
    up = time.monotonic() - start
    stop = time.monotonic()
    for node in nodes:
        node.send_signal(signal.SIGINT)
    codes = [node.wait(30) for node in nodes]
    down = time.monotonic() - stop
    if any(codes):
        raise SystemExit(f'turtlesim_node exited with {codes}:\n' + '\n'.join(node.output for node in nodes))
    return up, down


def report(name: str, samples: list[float], baseline: list[float] | None = None) -> None:
    """Print one row: median and max of samples (s) in ms, and with a baseline the ratio of medians."""
    values = [ms(s) for s in samples]
    line = f'{name:<42} median {statistics.median(values):7.1f} ms   max {max(values):7.1f} ms'
    if baseline is not None:
        line += f'   {statistics.median(samples) / statistics.median(baseline):5.2f}x direct'
    print(line)


def main() -> None:
    """Time a one-process launch, turtle.launch.py and the direct baseline --repeat times each; print."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--repeat', type=int, default=5)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory, RosSandbox() as sandbox:
        sleeper = Path(directory) / 'sleeper.launch.xml'
        sleeper.write_text(SLEEPER)
        process_up, process_down, turtles_up, turtles_down, direct_up, direct_down = [], [], [], [], [], []
        for _ in range(args.repeat):
            up, down = launch_and_stop(sandbox, [str(sleeper)], STARTED, 1)
            process_up.append(up)
            process_down.append(down)
            up, down = launch_and_stop(
                sandbox, ['turtle.launch.py'], r'Spawning turtle \[turtle1\]', 2,
                cwd=str(ROOT / 'src' / 'course' / 'olive_launch' / 'launch'))
            turtles_up.append(up)
            turtles_down.append(down)
            up, down = start_and_stop_directly(sandbox)
            direct_up.append(up)
            direct_down.append(down)
    report('ros2 launch -> process started', process_up)
    report('Ctrl-C -> launch exited (sleep)', process_down)
    report('ros2 launch -> both turtlesim nodes spawned', turtles_up, direct_up)
    report('Ctrl-C -> launch exited (2 turtlesim)', turtles_down, direct_down)
    report('baseline: both turtlesim nodes spawned', direct_up)
    report('baseline: Ctrl-C -> both exited', direct_down)


if __name__ == '__main__':
    main()
