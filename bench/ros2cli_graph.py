"""`ros2` CLI latency and throughput against one graph of 20 nodes, in a private ROS domain.

Measures, in one run:
- wall time of `ros2 topic list`, `ros2 node list`, `ros2 param get` cold (--no-daemon), with a
  daemon started just before (`ros2 daemon start`, then the call), and warm (daemon running), and
  whether each listing saw all 20 nodes / topics; targets: cold median <= 0.6 s and complete in
  every run, warm <= 0.15 s (the fresh daemon has no target: it is shown for completeness). Warm
  calls start once the daemon is DAEMON_SETTLED s old: a younger one is still asked whether its
  graph has settled, as in the fresh case (0.19-0.26 s per call before 1.5 s of age). The three
  measurements below run while it ages (none of them asks the daemon); their lines follow the table;
- `ros2 topic hz` on a 100 Hz publisher (target 100 +- 1 Hz);
- `ros2 topic pub -r 100` as measured by a subscriber here (target 100 +- 1 Hz);
- `ros2 topic echo` of a 1 kHz std_msgs/Int32 stream: messages lost (target 0).

The baseline, run in the same invocation, is a bare rclpy script doing what a cold CLI call
must do: start Python, create a node, wait 0.5 s for discovery (upstream's fixed wait), list the
nodes. Ratios are ours / baseline.
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import time
from collections.abc import Callable

from owl_common.processes import RosSandbox
from ros2cli.node.strategy import DAEMON_SETTLED

NODES = 20
FIXTURES = 'ros2cli_test_fixtures'
BASELINE = """
import rclpy
from rclpy.node import Node
rclpy.init()
node = Node('_baseline')
end = node.get_clock().now().nanoseconds + 500_000_000
while node.get_clock().now().nanoseconds < end:
    rclpy.spin_once(node, timeout_sec=0.05)
print('\\n'.join(sorted(node.get_node_names())))
"""


def timed(sandbox: RosSandbox, argv: list[str]) -> tuple[float, str]:
    """(wall time in s, stdout) of one run of argv in the sandbox's environment."""
    started = time.perf_counter()
    result = subprocess.run(argv, env=sandbox.env, capture_output=True, text=True, timeout=60, check=False)
    return time.perf_counter() - started, result.stdout


def sample(sandbox: RosSandbox, argv: list[str], runs: int, complete: re.Pattern[str],
           before: list[list[str]] | None = None) -> tuple[float, int]:
    """Median wall time of argv over runs, and how many of the runs saw all NODES entities.

    The commands in before run (untimed) ahead of each run.
    """
    times, full = [], 0
    for _ in range(runs):
        for command in before or []:
            subprocess.run(command, env=sandbox.env, capture_output=True, check=False, timeout=60)
        seconds, output = timed(sandbox, argv)
        times.append(seconds)
        full += len(complete.findall(output)) >= NODES if complete.pattern else 1
    return statistics.median(times), full


def wait_for_graph(sandbox: RosSandbox) -> None:
    """Return once `ros2 node list` shows all NODES graph nodes; exit the bench if not within 60 s."""
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        _, output = timed(sandbox, ['ros2', 'node', 'list'])
        if len(re.findall(r'/graph_node_\d+', output)) == NODES:
            return
        time.sleep(0.5)
    raise SystemExit('the 20-node graph did not come up within 60 s')


def latency(sandbox: RosSandbox, runs: int, while_the_daemon_ages: Callable[[], None]) -> None:
    """Print the baseline, then each verb's cold, fresh-daemon and warm wall time against its target.

    while_the_daemon_ages runs once the warm daemon is started: its DAEMON_SETTLED s of ageing need
    nothing of this process.
    """
    node_pattern = re.compile(r'^/graph_node_\d+$', re.M)
    topic_pattern = re.compile(r'^/graph_topic_\d+$', re.M)
    verbs = [
        ('topic list', ['ros2', 'topic', 'list'], topic_pattern),
        ('node list', ['ros2', 'node', 'list'], node_pattern),
        ('param get', ['ros2', 'param', 'get', '/graph_node_07', 'index'], re.compile('')),
    ]
    baseline, baseline_full = sample(sandbox, [sys.executable, '-c', BASELINE], runs,
                                     re.compile(r'^graph_node_\d+$', re.M))
    print(f'baseline (bare rclpy node, 0.5 s discovery): {baseline:.3f} s, all {NODES} nodes seen in '
          f'{baseline_full}/{runs} runs')
    daemon_stop = ['ros2', 'daemon', 'stop']
    subprocess.run(daemon_stop, env=sandbox.env, capture_output=True, check=False)
    print(f"{'verb':<12} {'mode':<6} {'median s':>9} {'target':>7} {'complete':>9} {'x baseline':>11}")
    for mode, extra, target in (('cold', ['--no-daemon'], 0.6), ('fresh', [], None), ('warm', [], 0.15)):
        if mode == 'warm':
            started = time.monotonic()
            subprocess.run(['ros2', 'daemon', 'start'], env=sandbox.env, capture_output=True, check=False)
            while_the_daemon_ages()
            wait_for_graph(sandbox)
            # Until then a verb checks with the daemon that its graph has settled (the fresh case).
            time.sleep(max(0.0, started + DAEMON_SETTLED - time.monotonic()))
        before = [daemon_stop, ['ros2', 'daemon', 'start']] if mode == 'fresh' else []
        for name, argv, complete in verbs:
            seconds, full = sample(sandbox, argv + extra, runs, complete, before)
            verdict = '' if target is None else 'ok' if seconds <= target and full == runs else 'MISS'
            print(f"{name:<12} {mode:<6} {seconds:>9.3f} {'-' if target is None else f'{target:.2f}s':>7} "
                  f'{full:>4}/{runs:<4} {seconds / baseline:>10.2f}  {verdict}')
        if mode == 'fresh':
            subprocess.run(daemon_stop, env=sandbox.env, capture_output=True, check=False)


def hz(sandbox: RosSandbox, seconds: float) -> str:
    """The last rate `ros2 topic hz` reports for a 100 Hz counter after `seconds`, against 100 +- 1.

    If its first report comes later than that (a short run), that report.
    """
    counter = sandbox.run(FIXTURES, 'counter', '--ros-args', '-p', 'rate:=100.0', '-r', 'count:=/hz_count')
    process = sandbox.command(['ros2', 'topic', 'hz', '/hz_count'])
    started = time.monotonic()
    report = r'average rate: (\d+\.\d+)'
    try:
        process.wait_for(report, timeout=max(seconds, 30.0))
    except AssertionError:
        pass  # no report: said below
    time.sleep(max(0.0, started + seconds - time.monotonic()))
    process.stop()
    counter.stop()
    rates = [float(m) for m in re.findall(report, process.output)]
    if not rates:
        return 'topic hz: no report'
    return (f'topic hz on a 100 Hz publisher: {rates[-1]:.3f} Hz (target 100 +- 1) '
            f"{'ok' if abs(rates[-1] - 100) <= 1 else 'MISS'}")


def pub_rate(sandbox: RosSandbox, seconds: float) -> str:
    """The rate of `ros2 topic pub -r 100` a subscriber here measures over `seconds` past its first second."""
    import rclpy
    from rclpy.context import Context
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.node import Node
    from std_msgs.msg import Int32

    context = Context()
    rclpy.init(context=context, domain_id=sandbox.domain_id)
    node = Node('bench_subscriber', context=context)
    arrivals: list[float] = []
    node.create_subscription(Int32, '/pub_rate', lambda _m: arrivals.append(time.monotonic()), 100)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    publisher = sandbox.command(['ros2', 'topic', 'pub', '-p', '0', '-r', '100', '/pub_rate',
                                 'std_msgs/msg/Int32', '{data: 1}'])
    deadline = time.monotonic() + 60.0  # for the first message
    while not arrivals and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)
    if arrivals:
        deadline = arrivals[0] + 1.0 + seconds
        while time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
    publisher.stop()
    # Before the context goes: Jazzy's Executor.__del__ otherwise destroys its guard condition
    # after the context did, and prints an "Exception ignored" traceback.
    executor.shutdown()
    node.destroy_node()
    rclpy.try_shutdown(context=context)
    window = [t for t in arrivals if t >= arrivals[0] + 1.0] if arrivals else []
    if len(window) < 2:
        return 'topic pub -r 100: nothing received'
    rate = (len(window) - 1) / (window[-1] - window[0])
    return (f'topic pub -r 100 measured by a subscriber: {rate:.3f} Hz (target 100 +- 1) '
            f"{'ok' if abs(rate - 100) <= 1 else 'MISS'}")


def echo_loss(sandbox: RosSandbox, count: int) -> str:
    """How many of `count` Int32 messages at 1 kHz a reliable `ros2 topic echo` did not print."""
    # The counter's own policies: a late-matching echo still gets the first messages of the burst,
    # so any loss is echo falling more than 1000 messages behind.
    echo = sandbox.command(['ros2', 'topic', 'echo', '--qos-reliability', 'reliable', '--qos-durability',
                            'transient_local', '--qos-depth', '1000', '--field', 'data', '/echo_count',
                            'std_msgs/msg/Int32'])
    counter = sandbox.run(FIXTURES, 'counter', '--ros-args', '-p', 'rate:=1000.0', '-p', f'limit:={count}',
                          '-p', 'wait_for:=1', '-r', 'count:=/echo_count')
    counter.wait_for(f'published {count} messages', timeout=60)
    # Up to 1 s more for echo to catch up; done once it printed the last one (in order: reliable, one
    # writer), for whatever it lost is lost by then.
    deadline, last, seen = time.monotonic() + 1.0, str(count), 0
    while time.monotonic() < deadline:
        new = echo.lines[seen:]
        seen += len(new)
        if last in new:
            break
        time.sleep(0.01)
    echo.stop()
    counter.stop()
    received = [int(line) for line in echo.lines if line.isdigit()]
    lost = count - len(set(received))
    return (f'topic echo (reliable, depth 1000) of a 1 kHz Int32 stream: {len(set(received))}/{count} '
            f"received, {lost} lost (target 0) {'ok' if lost == 0 else 'MISS'}")


def main() -> None:
    """Bring up the 20-node graph and run every measurement on it; the daemon is stopped at the end."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--runs', type=int, default=20, help='runs per latency measurement')
    parser.add_argument('--seconds', type=float, default=8.0, help='length of the hz / pub measurements')
    parser.add_argument('--messages', type=int, default=5000, help='messages of the echo loss test')
    args = parser.parse_args()
    with RosSandbox() as sandbox:
        graph = sandbox.run(FIXTURES, 'graph_nodes', str(NODES))
        graph.wait_for(f'{NODES} nodes up', timeout=60)
        try:
            wait_for_graph(sandbox)
            lines: list[str] = []

            def rates_and_loss() -> None:
                lines.extend((hz(sandbox, args.seconds), pub_rate(sandbox, args.seconds),
                              echo_loss(sandbox, args.messages)))

            latency(sandbox, args.runs, rates_and_loss)
            print('\n'.join(lines))
        finally:
            subprocess.run(['ros2', 'daemon', 'stop'], env=sandbox.env, capture_output=True, check=False)


if __name__ == '__main__':
    main()
