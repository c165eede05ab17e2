"""How often a node hangs in clean-up when two of them are stopped together with Ctrl-C.

A suspected Fast DDS teardown deadlock (the eProsima/Fast-DDS#6502 shape) once left a turtlesim
node running after `ros2 launch` stopped two of them. This repeats that stop: per pair, two nodes
start together in one private ROS domain; once both are spinning and in the graph, both get SIGINT
at the same moment. Each process is then classified:
- clean: exit 0 within 3 s of the SIGINT (exit 0 later is counted as slow);
- watchdog: exit 1 with owl_common.run's teardown watchdog stack dump (a hang, caught after 5 s);
- alive: still running 8 s after the SIGINT (hung beyond the watchdog): its native stacks are
  printed (gdb, when installed) and it is killed;
- other: any other exit code or a signal (a crash).
The first occurrence of each non-clean kind prints the first lines of its stack or output.

The baseline, measured in the same run and interleaved pair by pair with the turtlesim nodes (so
both see the same machine load), is a bare rclpy node spun with rclpy.spin. --hogs busy-loop
processes compete for the CPU during the whole run, as in the run that once hung. The hung rate's
95 % upper bound is the exact one-sided binomial (Clopper-Pearson) bound: for a count of 0 it is
1 - 0.05^(1/n), the rule of three's 3/n.
"""

from __future__ import annotations

import argparse
import importlib.metadata
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from collections import Counter
from collections.abc import Callable
from contextlib import ExitStack

import rclpy
from measure import percentile
from owl_common.processes import RosProcess, RosSandbox
from rclpy.context import Context
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

CLEAN_LIMIT = 3.0  # s: a clean stop exits by then (normally well under 1 s)
# s: past owl_common.run's 5 s teardown watchdog with slack for a loaded machine; alive by then
# means the watchdog did not fire (or the node has none, as the baseline).
KILL_AFTER = 8.0
POLL = 0.01  # s: resolution of the measured stop latency
WATCHDOG_DUMP = re.compile(r'^Timeout \([\d:.]+\)!$', re.MULTILINE)  # faulthandler's header
SHOWN_LINES = 40  # of a Python stack dump or an output
NATIVE_FRAMES = 4  # per thread
NATIVE_WIDTH = 160
LIBRARY_FRAME = r'(nptl|sysdeps)/|libstdc\+\+|start_thread|clone3| syscall '
HOG = 'while True: pass'
TURTLESIM_READY = r'Spawning turtle \[turtle1\]'  # the constructor's last line; spinning next
BASELINE_READY = r' spinning$'


def baseline_node(name: str) -> None:
    """The baseline: a bare rclpy node as the course writes one, with rclpy's own signal handling."""
    rclpy.init()
    node = Node(name)
    try:
        print(f'{name} spinning', flush=True)
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


def start_turtlesim(sandbox: RosSandbox, name: str) -> RosProcess:
    """A headless turtlesim_node named `name` in the sandbox: the node that once hung."""
    return sandbox.run('turtlesim', 'turtlesim_node', '--headless', '--ros-args', '-r', f'__node:={name}',
                       label=name)


def start_baseline(sandbox: RosSandbox, name: str) -> RosProcess:
    """This script as the baseline node `name` (--baseline-node) in the sandbox."""
    return sandbox.command([sys.executable, __file__, '--baseline-node', name], label=name)


def upper_bound(count: int, total: int, confidence: float = 0.95) -> float:
    """Exact one-sided upper confidence bound of a rate seen `count` times in `total` trials."""
    def at_most_count(rate: float) -> float:
        return sum(math.comb(total, k) * rate ** k * (1 - rate) ** (total - k) for k in range(count + 1))

    low, high = count / total, 1.0
    for _ in range(50):  # bisection: at_most_count falls as the rate rises
        middle = (low + high) / 2
        if at_most_count(middle) > 1 - confidence:
            low = middle
        else:
            high = middle
    return high


def native_stacks(pid: int) -> str:
    """Every thread's innermost native frames, from gdb, or one line saying why there are none.

    Fast DDS threads are not Python threads, so the watchdog's dump cannot show them.
    """
    gdb = shutil.which('gdb')
    if gdb is None:
        return '(no gdb on PATH: no native stacks)'
    result = subprocess.run([gdb, '-p', str(pid), '-batch', '-ex', 'thread apply all bt'],
                            capture_output=True, text=True, timeout=120, check=False)
    lines: list[str] = []
    for line in result.stdout.splitlines():
        if line.startswith('Thread '):
            lines.append(line)
            shown = 0
        # What each thread waits in, without the libc and libstdc++ frames every waiting thread has
        # and the addresses; C++ template names run to pages, so each frame is cut short.
        elif line.startswith('#') and shown < NATIVE_FRAMES and not re.search(LIBRARY_FRAME, line):
            lines.append('    ' + re.sub(r'^#\d+\s+(0x[0-9a-f]+ in )?', '', line)[:NATIVE_WIDTH])
            shown += 1
    return '\n'.join(lines) or f'(gdb found no stacks: {result.stderr.strip()[-300:]})'


def exit_name(code: int) -> str:
    """How a process ended, for the report: a signal's name (e.g. SIGKILL) if code < 0, else 'exit N'."""
    return signal.Signals(-code).name if code < 0 else f'exit {code}'


class Graph:
    """A participant in a sandbox's domain that sees which nodes are up."""

    def __init__(self, domain_id: int) -> None:
        self.context = Context()
        # The benchmark's own Ctrl-C must stay a plain KeyboardInterrupt.
        rclpy.init(context=self.context, domain_id=domain_id,
                   signal_handler_options=SignalHandlerOptions.NO)
        self.node = Node(f'teardown_observer_{domain_id}', context=self.context)

    def wait_for(self, names: list[str], timeout: float) -> None:
        """Wait until every node named is in the graph (the graph cache needs no spinning)."""
        deadline = time.monotonic() + timeout
        while True:
            missing = set(names) - {name for name, _ in self.node.get_node_names_and_namespaces()}
            if not missing:
                return
            if time.monotonic() > deadline:
                raise AssertionError(f'not in the graph after {timeout:.0f} s: {sorted(missing)}')
            time.sleep(0.05)

    def close(self) -> None:
        """Destroy the observer node and shut its context down."""
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)


class PairLoop:
    """One kind of node: its sandbox, its graph observer and the tally of its stops."""

    def __init__(self, label: str, start: Callable[[RosSandbox, str], RosProcess], ready: str,
                 resources: ExitStack) -> None:
        self.label = label
        self.start = start
        self.ready = ready
        self.sandbox = resources.enter_context(RosSandbox())
        self.graph = Graph(self.sandbox.domain_id)
        resources.callback(self.graph.close)
        self.stops: list[float] = []
        self.counts: Counter[str] = Counter()
        self.others: Counter[str] = Counter()
        self.shown: set[str] = set()

    def show_once(self, kind: str, process: RosProcess, what: str, text: str,
                  limit: int | None = SHOWN_LINES) -> None:
        """Print text's first `limit` lines (all with None) the first time `kind` happens; else nothing."""
        if kind in self.shown:
            return
        self.shown.add(kind)
        lines = text.splitlines()[:limit]
        print(f'--- {self.label}: first {kind} ({process.label}, pid {process.pid}); {what}, '
              f'first {len(lines)} lines:', *lines, '---', sep='\n', flush=True)

    def run_pair(self, index: int, start_timeout: float) -> None:
        """Start two nodes, SIGINT both at once when both spin and are in the graph, and classify them.

        A pair not up within start_timeout is counted as a start failure and stopped.
        """
        names = [f'{self.label.replace(" ", "_")}_{index}_{side}' for side in 'ab']
        processes = [self.start(self.sandbox, name) for name in names]
        try:
            deadline = time.monotonic() + start_timeout
            for process in processes:
                process.wait_for(self.ready, timeout=max(0.1, deadline - time.monotonic()))
            self.graph.wait_for(names, timeout=max(0.1, deadline - time.monotonic()))
        except AssertionError as error:
            self.counts['start failures'] += 1
            self.show_once('start failure', processes[0], 'the error', str(error))
            for process in processes:
                process.stop(timeout=3.0)
            return
        sent = time.monotonic()
        for process in processes:  # back to back: as one Ctrl-C to a launch of both
            process.send_signal(signal.SIGINT)
        ended: list[float | None] = [None] * len(processes)
        stacks_taken = False
        while None in ended and time.monotonic() - sent < KILL_AFTER:
            for slot, process in enumerate(processes):
                if ended[slot] is None and not process.running():
                    ended[slot] = time.monotonic() - sent
            late = [process for slot, process in enumerate(processes) if ended[slot] is None]
            if late and not stacks_taken and time.monotonic() - sent > CLEAN_LIMIT:
                # Native stacks while it hangs: the watchdog ends it before KILL_AFTER.
                self.show_once('process alive 3 s after SIGINT', late[0], 'native stacks',
                               native_stacks(late[0].pid), limit=None)
                stacks_taken = True
            time.sleep(POLL)
        for process, elapsed in zip(processes, ended, strict=True):
            self.classify(process, elapsed)

    def classify(self, process: RosProcess, elapsed: float | None) -> None:
        """Count how one process ended, `elapsed` s after the SIGINT; None: alive at KILL_AFTER, so killed."""
        self.counts['processes'] += 1
        if elapsed is None:
            self.counts['alive'] += 1
            self.show_once('process alive 8 s after SIGINT', process, 'native stacks',
                           native_stacks(process.pid), limit=None)
            process.send_signal(signal.SIGKILL)
            process.wait(10)
            return
        code = process.wait(10)  # also reads the rest of its output
        self.stops.append(elapsed)
        dump = WATCHDOG_DUMP.search(process.output)
        if code == 0:
            self.counts['clean' if elapsed <= CLEAN_LIMIT else 'slow'] += 1
        elif code == 1 and dump:
            self.counts['watchdog'] += 1
            self.show_once('watchdog exit', process, 'its stack dump', process.output[dump.start():])
        else:
            self.others[exit_name(code)] += 1
            self.show_once(f'{exit_name(code)}', process, 'its output', process.tail(SHOWN_LINES))

    @property
    def hung(self) -> int:
        """Processes that hung in clean-up: ended by the watchdog or alive at KILL_AFTER."""
        return self.counts['watchdog'] + self.counts['alive']

    @property
    def hung_rate(self) -> float:
        """Hung processes as a fraction of all the processes stopped."""
        return self.hung / self.counts['processes']

    def report(self) -> None:
        """Print the tally: hung rate with its 95 % upper bound, other exits, clean and slow ones, stops."""
        total = self.counts['processes']
        if total == 0:
            print(f'{self.label}: no process got as far as the stop '
                  f'({self.counts["start failures"]} pairs failed to start)')
            return
        others = ', '.join(f'{count} {name}' for name, count in sorted(self.others.items())) or 'none'
        print(f'{self.label}: {total} processes, {self.hung} hung ({100 * self.hung_rate:.2f} %, '
              f'95 % upper bound {100 * upper_bound(self.hung, total):.1f} %): '
              f'{self.counts["watchdog"]} watchdog exits, {self.counts["alive"]} alive after '
              f'{KILL_AFTER:.0f} s; {sum(self.others.values())} crashes or other exits ({others}); '
              f'{self.counts["clean"]} clean, {self.counts["slow"]} exit 0 after {CLEAN_LIMIT:.0f} s; '
              f'{self.counts["start failures"]} pairs failed to start; '
              f'stop p50 {percentile(self.stops, 0.5):.2f} s p99 {percentile(self.stops, 0.99):.2f} s '
              f'max {max(self.stops):.2f} s')


def version(*distributions: str) -> str:
    """The version of the first of these wheels that is installed, '?' when none is.

    Fast DDS 3 is ros-fastdds, 2.x ros-fastrtps. For rclpy it is the ros-rclpy wheel's version, not
    that of the rclpy egg-info inside it.
    """
    for distribution in distributions:
        try:
            return importlib.metadata.version(distribution)
        except importlib.metadata.PackageNotFoundError:
            pass
    return '?'


def main() -> int:
    """Stop --pairs pairs of each kind, interleaved, and print the reports; --baseline-node: be that node."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--pairs', type=int, default=150, help='pairs stopped per kind of node')
    parser.add_argument('--hogs', type=int, default=2, help='busy-loop CPU hog processes during the run')
    parser.add_argument('--start-timeout', type=float, default=30.0,
                        help='s for both nodes of a pair to be up; a pair that is not is counted and skipped')
    parser.add_argument('--baseline-node', metavar='NAME', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.baseline_node:
        baseline_node(args.baseline_node)
        return 0

    print(f'{args.pairs} pairs per kind, {args.hogs} CPU hogs, {os.cpu_count()} cores; '
          f'rclpy {version("ros-rclpy")}, Fast DDS {version("ros-fastdds", "ros-fastrtps")}', flush=True)
    started = time.monotonic()
    with ExitStack() as resources:
        loops = [PairLoop('turtlesim', start_turtlesim, TURTLESIM_READY, resources),
                 PairLoop('bare rclpy', start_baseline, BASELINE_READY, resources)]
        for _ in range(args.hogs):
            hog = RosProcess([sys.executable, '-c', HOG], dict(os.environ), label='cpu hog')
            resources.callback(hog.stop, 1.0)
        every = max(1, args.pairs // 10)
        for index in range(args.pairs):
            for loop in loops:  # interleaved: both kinds see the same load over the run
                loop.run_pair(index, args.start_timeout)
            if (index + 1) % every == 0:
                print(f'pair {index + 1}/{args.pairs} after {time.monotonic() - started:.0f} s: '
                      + ', '.join(f'{loop.label} {loop.hung} hung' for loop in loops), flush=True)
    print()
    for loop in loops:
        loop.report()
    turtlesim, baseline = loops
    if turtlesim.stops and baseline.stops:
        hung_ratio = (f'{turtlesim.hung_rate / baseline.hung_rate:.2f}x' if baseline.hung
                      else 'n/a (0 hung in the baseline)')
        print(f'turtlesim / bare rclpy: stop p50 '
              f'{percentile(turtlesim.stops, 0.5) / percentile(baseline.stops, 0.5):.2f}x, p99 '
              f'{percentile(turtlesim.stops, 0.99) / percentile(baseline.stops, 0.99):.2f}x; '
              f'hung rate {hung_ratio}')
    print(f'run time {time.monotonic() - started:.0f} s')
    return 0


if __name__ == '__main__':
    sys.exit(main())
