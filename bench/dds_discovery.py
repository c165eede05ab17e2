"""How long a new process takes to see a running node's topic: Fast DDS defaults vs config/fastdds.xml.

Starts one publisher (plus --others idle nodes) in a private domain, then runs --runs fresh
processes one after another, each timing from node creation until the publisher's topic is in its
graph. The baseline is the same measurement without our profile, in the same invocation.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

from owl_common.processes import RosSandbox

PROFILE = Path(__file__).resolve().parents[1] / 'config' / 'fastdds.xml'
TOPIC = '/discovery_target'

PUBLISHER = '''
import sys, rclpy
from std_msgs.msg import Int32
rclpy.init()
node = rclpy.create_node(sys.argv[1])
node.create_publisher(Int32, sys.argv[2], 10)
try:
    rclpy.spin(node)
except KeyboardInterrupt:
    pass
'''

WATCHER = '''
import sys, time, rclpy
rclpy.init()
node = rclpy.create_node('discovery_watcher')
start = time.monotonic()
while time.monotonic() - start < 10.0:
    rclpy.spin_once(node, timeout_sec=0.005)
    if any(name == sys.argv[1] for name, _ in node.get_topic_names_and_types()):
        break
print(f'{time.monotonic() - start:.4f}')
'''


def measure(profile: str | None, runs: int, others: int) -> list[float]:
    env_update = {'FASTDDS_DEFAULT_PROFILES_FILE': profile or ''}
    with RosSandbox() as sandbox:
        sandbox.env.update(env_update)
        if profile is None:
            sandbox.env.pop('FASTDDS_DEFAULT_PROFILES_FILE')
        for index in range(others):
            sandbox.command([sys.executable, '-c', PUBLISHER, f'idle_{index}', f'/idle_{index}'])
        sandbox.command([sys.executable, '-c', PUBLISHER, 'discovery_target', TOPIC])
        time.sleep(3.0)  # everything up and known to each other before the first watcher
        times = []
        for _ in range(runs):
            done = subprocess.run([sys.executable, '-c', WATCHER, TOPIC], env=sandbox.env,
                                  capture_output=True, text=True, timeout=30)
            times.append(float(done.stdout.strip()))
    return sorted(times)


def summary(times: list[float]) -> str:
    def at(fraction: float) -> float:
        return times[min(len(times) - 1, int(fraction * len(times)))]
    return f'p50 {at(0.5):.3f} s  p90 {at(0.9):.3f} s  max {times[-1]:.3f} s'


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--runs', type=int, default=20)
    parser.add_argument('--others', type=int, default=5, help='idle nodes besides the publisher')
    args = parser.parse_args()
    os.environ.pop('FASTDDS_DEFAULT_PROFILES_FILE', None)
    baseline = measure(None, args.runs, args.others)
    ours = measure(str(PROFILE), args.runs, args.others)
    print(f'time for a new process to see a topic ({args.runs} runs, {args.others + 1} nodes running)')
    print(f'  Fast DDS defaults   : {summary(baseline)}')
    print(f'  config/fastdds.xml  : {summary(ours)}')
    print(f'ratio ours/defaults: p90 {ours[int(0.9 * len(ours))] / baseline[int(0.9 * len(baseline))]:.2f}x, '
          f'max {ours[-1] / baseline[-1]:.2f}x')
    return 0


if __name__ == '__main__':
    sys.exit(main())
