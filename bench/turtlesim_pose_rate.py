"""turtlesim_node's pose stream and CPU use, against a bare rclpy baseline measured in the same run.

Scenarios: 1 idle turtle, and 20 turtles driving circles (trails on). For each, the publisher is
first turtlesim_node (headless, or windowed with --window when a display exists), then the
baseline: a minimal rclpy node publishing the same number of Pose topics on a 16 ms timer and
doing nothing else. From the publisher's source timestamps of /turtle1/pose this reports the rate
and the interval percentiles (p99 jitter = p99 of |interval - 16 ms|); CPU is the publisher
process's user+system time over the window, in % of one core. Ratios are turtlesim / baseline;
the target for 20 moving turtles is at most twice the baseline's CPU.
"""

from __future__ import annotations

import argparse
import itertools
import os
import sys
import time
from dataclasses import dataclass

import rclpy
from geometry_msgs.msg import Twist
from measure import cpu_seconds, percentile
from owl_common.processes import RosSandbox
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile
from turtlesim.msg import Pose
from turtlesim.srv import Spawn

NOMINAL_MS = 16.0
CPU_TARGET = 2.0  # 20 moving turtles: at most this many times the bare publisher's CPU
QOS = QoSProfile(depth=7)


@dataclass
class Measurement:
    """What one publisher did over a measuring window, as one row of the printed table.

    rate_hz: /turtle1/pose messages a second; p50_ms, p99_ms: interval percentiles; p99_jitter_ms: p99
    of |interval - 16 ms|; cpu_percent: the publisher process's CPU in % of one core.
    """

    rate_hz: float
    p50_ms: float
    p99_ms: float
    p99_jitter_ms: float
    cpu_percent: float


def baseline_publisher(turtles: int) -> None:
    """The baseline process: `turtles` Pose publishers on one 16 ms timer, nothing else."""
    rclpy.init()
    node = Node('pose_baseline')
    publishers = [node.create_publisher(Pose, f'turtle{i + 1}/pose', QOS) for i in range(turtles)]

    def tick() -> None:
        for publisher in publishers:
            publisher.publish(Pose(x=1.0, y=1.0))

    node.create_timer(NOMINAL_MS / 1000.0, tick)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()



class Observer:
    """The bench's own node in the sandbox's domain."""

    def __init__(self, domain_id: int) -> None:
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = Node('pose_rate_bench', context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)

    def close(self) -> None:
        """Shut the executor down, then the context."""
        self.executor.shutdown()  # before its context (Jazzy's Executor.__del__ would print a traceback)
        rclpy.try_shutdown(context=self.context)

    def spin_for(self, seconds: float) -> None:
        """Spin the bench's node for `seconds`."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.executor.spin_once(timeout_sec=0.05)

    def wait_for(self, condition, seconds: float, what: str) -> None:
        """Spin until condition() is true; after `seconds`, exit the bench (SystemExit) naming `what`."""
        deadline = time.monotonic() + seconds
        while not condition():
            if time.monotonic() > deadline:
                raise SystemExit(f'timed out waiting for {what}')
            self.executor.spin_once(timeout_sec=0.05)

    def spawn(self, count: int) -> None:
        """Spawn `count` more turtles through /spawn, one call at a time, in a row along y = 2."""
        client = self.node.create_client(Spawn, '/spawn')
        self.wait_for(client.service_is_ready, 30, '/spawn')
        for index in range(count):
            future = client.call_async(Spawn.Request(x=1.0 + 0.45 * index, y=2.0, theta=0.0))
            self.wait_for(future.done, 10, 'a spawn')
        self.node.destroy_client(client)

    def measure(self, pid: int, turtles: int, moving: bool, seconds: float) -> Measurement:
        """/turtle1/pose's timing and process pid's CPU over `seconds`; with moving, every turtle circles."""
        stamps: list[int] = []

        def on_pose(_msg: Pose, info: dict[str, int]) -> None:
            stamps.append(info['source_timestamp'])

        subscription = self.node.create_subscription(
            Pose, '/turtle1/pose', on_pose, QOS)  # type: ignore[arg-type]  # rclpy's hint omits (msg, info)
        drivers = []
        if moving:
            drivers = [self.node.create_publisher(Twist, f'/turtle{i + 1}/cmd_vel', QOS)
                       for i in range(turtles)]
        self.wait_for(lambda: len(stamps) > 10, 30, 'poses')
        circle = Twist()
        circle.linear.x, circle.angular.z = 1.0, 0.8
        stamps.clear()
        cpu_start, wall_start = cpu_seconds(pid), time.monotonic()
        next_command = 0.0
        while time.monotonic() - wall_start < seconds:
            if moving and time.monotonic() >= next_command:
                for driver in drivers:  # refreshed twice a second, well inside the 1 s timeout
                    driver.publish(circle)
                next_command = time.monotonic() + 0.5
            self.executor.spin_once(timeout_sec=0.05)
        cpu = (cpu_seconds(pid) - cpu_start) / (time.monotonic() - wall_start) * 100.0
        self.node.destroy_subscription(subscription)
        for driver in drivers:
            self.node.destroy_publisher(driver)
        intervals = [(b - a) / 1e6 for a, b in itertools.pairwise(stamps)]
        if not intervals:
            raise SystemExit('no poses received')
        span_s = (stamps[-1] - stamps[0]) / 1e9
        return Measurement(
            rate_hz=len(intervals) / span_s, p50_ms=percentile(intervals, 0.5),
            p99_ms=percentile(intervals, 0.99),
            p99_jitter_ms=percentile([abs(i - NOMINAL_MS) for i in intervals], 0.99), cpu_percent=cpu)


def run_scenario(turtles: int, moving: bool, seconds: float, window: bool) -> dict[str, Measurement]:
    """One scenario's measurements: turtlesim_node's, then the baseline's, each in a sandbox of its own."""
    results = {}
    for publisher in ('turtlesim_node', 'baseline'):
        with RosSandbox() as sandbox:
            if publisher == 'turtlesim_node':
                process = sandbox.run('turtlesim', 'turtlesim_node', *([] if window else ['--headless']))
                process.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
            else:
                process = sandbox.command([sys.executable, __file__, '--baseline', str(turtles)],
                                          label='baseline')
            observer = Observer(sandbox.domain_id)
            try:
                if publisher == 'turtlesim_node' and turtles > 1:
                    observer.spawn(turtles - 1)
                results[publisher] = observer.measure(process.pid, turtles, moving, seconds)
            finally:
                observer.close()
    return results


def main() -> int:
    """Run both scenarios and print each publisher's row and the ratios; --baseline N: be that publisher."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--seconds', type=float, default=30.0, help='measuring window per run')
    parser.add_argument('--window', action='store_true',
                        help='turtlesim_node with its window (needs DISPLAY)')
    parser.add_argument('--baseline', type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.baseline:
        baseline_publisher(args.baseline)
        return 0
    if args.window and not os.environ.get('DISPLAY'):
        parser.error('--window needs a DISPLAY (e.g. run under xvfb-run)')
    mode = 'windowed' if args.window else 'headless'
    print(f'turtlesim_node ({mode}) vs bare rclpy publisher, {args.seconds:g} s per run, '
          f'nominal {1000 / NOMINAL_MS:.1f} Hz')
    print(f'{"scenario":<22}{"publisher":<16}{"rate Hz":>9}{"p50 ms":>8}{"p99 ms":>8}'
          f'{"p99 jit":>9}{"CPU %":>7}')
    for turtles, moving in ((1, False), (20, True)):
        label = f'{turtles} turtle{"s" if turtles > 1 else ""} {"moving" if moving else "idle"}'
        results = run_scenario(turtles, moving, args.seconds, args.window)
        for publisher, m in results.items():
            print(f'{label:<22}{publisher:<16}{m.rate_hz:>9.2f}{m.p50_ms:>8.2f}{m.p99_ms:>8.2f}'
                  f'{m.p99_jitter_ms:>9.2f}{m.cpu_percent:>7.1f}')
        ours, base = results['turtlesim_node'], results['baseline']
        cpu_ratio = ours.cpu_percent / max(base.cpu_percent, 1e-3)
        print(f'{"":<22}{"ratio":<16}{ours.rate_hz / base.rate_hz:>9.2f}{"":>8}'
              f'{ours.p99_ms / base.p99_ms:>8.2f}{ours.p99_jitter_ms / max(base.p99_jitter_ms, 1e-3):>9.2f}'
              f'{cpu_ratio:>7.2f}')
        if moving:
            print(f'{label}: turtlesim_node uses {cpu_ratio:.2f}x the baseline\'s CPU '
                  f'(target <= {CPU_TARGET:.0f}x: {"met" if cpu_ratio <= CPU_TARGET else "NOT met"})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
