"""How long a new process takes to discover running nodes: Fast DDS defaults vs config/fastdds.xml.

Starts --nodes idle publisher processes (node idle_<i> publishing /idle_<i>) in a private domain,
then runs --runs fresh processes one after another, each timing from its node's creation until
(a) it sees /idle_0 and (b) it sees the whole graph: every idle_<i> node and its topic (what a
`ros2 node list` or `ros2 topic list` without the daemon needs). Also measured: the CPU the idle
nodes use for their periodic announcements. The baseline is Fast DDS's defaults, in the same
invocation; with --periods, variants of our profile with other announcement periods are measured
too (what a shorter period would still gain, for how much more idle CPU).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from measure import cpu_seconds, percentile
from owl_common.processes import RosSandbox

PROFILE = Path(__file__).resolve().parents[1] / 'config' / 'fastdds.xml'
# Jazzy's Fast DDS 2.14 reads the first name only, Fast DDS 3 (Kilted on) the second only.
PROFILE_VARIABLE = 'FASTRTPS_DEFAULT_PROFILES_FILE'
OTHER_PROFILE_VARIABLE = 'FASTDDS_DEFAULT_PROFILES_FILE'
OUR_PERIOD = '<nanosec>500000000</nanosec></leaseAnnouncement>'
WATCH_LIMIT = 5.0  # s; a watcher that has not seen everything by then reports this

PUBLISHER = '''
import sys, rclpy
from std_msgs.msg import Int32
rclpy.init()
node = rclpy.create_node(sys.argv[1])
node.create_publisher(Int32, '/' + sys.argv[1], 10)
print('up', flush=True)
try:
    rclpy.spin(node)
except KeyboardInterrupt:
    pass
'''

WATCHER = '''
import sys, time, rclpy
nodes, limit = int(sys.argv[1]), float(sys.argv[2])
rclpy.init()
node = rclpy.create_node('discovery_watcher')
start = time.monotonic()
first = whole = limit
while time.monotonic() - start < limit:
    rclpy.spin_once(node, timeout_sec=0.005)
    names = {name for name, _ in node.get_node_names_and_namespaces()}
    topics = {name for name, _ in node.get_topic_names_and_types()}
    now = time.monotonic() - start
    if first == limit and '/idle_0' in topics:
        first = now
    if all(f'idle_{i}' in names and f'/idle_{i}' in topics for i in range(nodes)):
        whole = now
        break
print(f'{first:.4f} {whole:.4f}')
'''


def measure(profile: str | None, runs: int, nodes: int, idle_seconds: float,
            settle_seconds: float) -> tuple[list[float], list[float], float]:
    """(times to the first topic, times to the whole graph, idle CPU % of all the nodes).

    The idle CPU is counted, and the first watcher starts, settle_seconds after the nodes are up.
    """
    with RosSandbox() as sandbox:
        for variable in (PROFILE_VARIABLE, OTHER_PROFILE_VARIABLE):
            sandbox.env.pop(variable, None)
        if profile is not None:
            sandbox.env[PROFILE_VARIABLE] = profile
        publishers = [sandbox.command([sys.executable, '-c', PUBLISHER, f'idle_{index}'])
                      for index in range(nodes)]
        # Start-up takes several seconds of CPU on a busy machine: idle means after it, not 3 s in.
        for publisher in publishers:
            publisher.wait_for('^up$', timeout=120)
        time.sleep(settle_seconds)  # past the initial announcements: all known to each other before a watcher
        cpu_before, started = sum(cpu_seconds(p.pid) for p in publishers), time.monotonic()
        time.sleep(idle_seconds)
        cpu_used = sum(cpu_seconds(p.pid) for p in publishers) - cpu_before
        idle_cpu = 100 * cpu_used / (time.monotonic() - started)
        first, whole = [], []
        for _ in range(runs):
            done = subprocess.run([sys.executable, '-c', WATCHER, str(nodes), str(WATCH_LIMIT)],
                                  env=sandbox.env, capture_output=True, text=True, timeout=30)
            seen_first, seen_whole = map(float, done.stdout.split())
            first.append(seen_first)
            whole.append(seen_whole)
    return first, whole, idle_cpu


def summary(times: list[float]) -> str:
    """The p50, p90 and max of times (s), as one column of the printed table."""
    return f'p50 {percentile(times, 0.5):.3f} s  p90 {percentile(times, 0.9):.3f} s  max {max(times):.3f} s'


def profile_with_period(directory: str, milliseconds: int) -> str:
    """Path of a copy of config/fastdds.xml, written in directory, that announces every `milliseconds` ms.

    Exits the bench (SystemExit) if the profile no longer has the 500 ms period this replaces.
    """
    path = os.path.join(directory, f'fastdds_{milliseconds}ms.xml')
    text = PROFILE.read_text()
    if OUR_PERIOD not in text:
        raise SystemExit('config/fastdds.xml no longer has the announcement period this bench varies')
    Path(path).write_text(text.replace(OUR_PERIOD, f'<nanosec>{milliseconds * 1_000_000}</nanosec>'
                                                   '</leaseAnnouncement>'))
    return path


def main() -> int:
    """Measure each profile variant and print its row, then the ratio ours / defaults; exit code 0."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--runs', type=int, default=20)
    parser.add_argument('--nodes', type=int, default=6, help='idle publisher processes running')
    parser.add_argument('--periods', type=int, nargs='*', default=[200, 100],
                        help='other announcement periods (ms) to measure as variants of our profile')
    parser.add_argument('--idle-seconds', type=float, default=5.0,
                        help="window of the running nodes' idle CPU measurement")
    parser.add_argument('--settle-seconds', type=float, default=2.0,
                        help='s after the nodes are up (past their initial announcements) before measuring')
    args = parser.parse_args()
    print(f'discovery by a new process ({args.runs} runs, {args.nodes} node processes running; '
          f'whole graph = every node and topic)')
    print(f"{'profile':<28} {'first topic':<38} {'whole graph':<38} idle CPU")
    with tempfile.TemporaryDirectory() as directory:
        variants = [('Fast DDS defaults', None), ('config/fastdds.xml (500 ms)', str(PROFILE))]
        variants += [(f'  same, announcing {ms} ms', profile_with_period(directory, ms))
                     for ms in args.periods]
        results = {}
        for label, profile in variants:
            first, whole, idle_cpu = measure(profile, args.runs, args.nodes, args.idle_seconds,
                                             args.settle_seconds)
            results[label] = whole
            print(f'{label:<28} {summary(first):<38} {summary(whole):<38} {idle_cpu:.1f} %', flush=True)
    baseline, ours = results['Fast DDS defaults'], results['config/fastdds.xml (500 ms)']
    print(f'ratio ours/defaults, whole graph: p50 {percentile(ours, 0.5) / percentile(baseline, 0.5):.2f}x, '
          f'p90 {percentile(ours, 0.9) / percentile(baseline, 0.9):.2f}x')
    return 0


if __name__ == '__main__':
    sys.exit(main())
