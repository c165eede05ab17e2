"""Service round-trip latency: temp_server against a minimal rclpy echo service, same run.

Both servers run as separate processes in a private ROS domain; this process is the client. Part 1
calls them in turn (temp_server, echo, temp_server, ...) from one fresh executor, N calls each, and
prints p50/p99 per server and their ratio (temp_server / echo): the cost of our server code and
logging over bare rclpy. Part 2 is the long run: LONG sequential calls to the echo service, each
awaited with executor.spin_until_future_complete and then with a spin_once loop (a fresh executor
each), and compares the mean of the last WINDOW calls with the first WINDOW: a client must keep its
first calls' latency (rclpy 7.1.6 alone left 3 Tasks per call in the executor; the venv's repair
drops them, see src/tools/owl_venv_hooks/owl_rclpy_repair.py). Target: last/first <= 1.2.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from typing import Any

import rclpy
from measure import percentile
from olive_interfaces.srv import TempConv
from owl_common.processes import RosSandbox
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

WARM_UP = 20
TARGET = 1.2  # last window's mean over the first's, long run


def echo_server() -> None:
    """The baseline: an rclpy service that answers at once with an empty response."""
    rclpy.init()
    node = Node('echo_service')
    node.create_service(TempConv, 'echo', lambda request, response: response)
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


def count_at_least(least: int) -> Callable[[str], int]:
    """An argparse type: a whole number of at least `least`, else argparse's one-line usage error."""
    def count(text: str) -> int:
        if not text.isdigit() or int(text) < least:
            raise argparse.ArgumentTypeError(f"'{text}' is not a whole number of at least {least}")
        return int(text)
    return count


def spin_until_complete(executor: SingleThreadedExecutor, future: Any) -> None:
    """Await a call with executor.spin_until_future_complete (10 s timeout): one awaiting style."""
    executor.spin_until_future_complete(future, timeout_sec=10.0)


def spin_once_loop(executor: SingleThreadedExecutor, future: Any) -> None:
    """Await a call with executor.spin_once in a loop until it is done, for up to 10 s: the other style."""
    deadline = time.monotonic() + 10.0
    while not future.done() and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.1)


def call(client: Any, executor: SingleThreadedExecutor, index: int,
         wait: Callable[[SingleThreadedExecutor, Any], None] = spin_until_complete) -> float:
    """Latency in ms of one TempConv call."""
    started = time.perf_counter()
    future = client.call_async(TempConv.Request(temp_c=float(index)))
    wait(executor, future)
    if not future.done():
        raise SystemExit(f'call {index} to {client.srv_name} timed out')
    return (time.perf_counter() - started) * 1000.0


def fresh_client(context: Context, services: list[str]) -> tuple[Node, SingleThreadedExecutor, list[Any]]:
    """A new node and executor, with a ready client per service."""
    executor = SingleThreadedExecutor(context=context)
    node = Node('bench_client', context=context)
    executor.add_node(node)
    clients = [node.create_client(TempConv, service) for service in services]
    for client in clients:
        if not client.wait_for_service(timeout_sec=30.0):
            raise SystemExit(f'service {client.srv_name} did not come up')
    return node, executor, clients


def interleaved(context: Context, services: list[str], calls: int) -> list[list[float]]:
    """Each service's latencies, the services called in turn (after WARM_UP rounds)."""
    node, executor, clients = fresh_client(context, services)
    try:
        results: list[list[float]] = [[] for _ in services]
        for index in range(calls + WARM_UP):
            for latencies, client in zip(results, clients, strict=True):
                latency = call(client, executor, index)
                if index >= WARM_UP:
                    latencies.append(latency)
        return results
    finally:
        executor.shutdown()
        node.destroy_node()


def long_run(context: Context, service: str, calls: int,
             wait: Callable[[SingleThreadedExecutor, Any], None]) -> list[float]:
    """Latencies (ms) of `calls` sequential calls to service from a fresh client, after WARM_UP calls."""
    node, executor, [client] = fresh_client(context, [service])
    try:
        latencies = [call(client, executor, index, wait) for index in range(calls + WARM_UP)]
        return latencies[WARM_UP:]
    finally:
        executor.shutdown()
        node.destroy_node()


def main() -> int:
    """Run both parts and print their tables (exit code 0); with --echo-server, be the baseline server."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--calls', type=count_at_least(1), default=1000, help='calls per server, part 1')
    parser.add_argument('--long-calls', type=count_at_least(10), default=10_000,
                        help='calls per awaiting style, part 2 (at least 10)')
    parser.add_argument('--echo-server', action='store_true', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.echo_server:
        echo_server()
        return 0
    window = min(1000, args.long_calls // 5)
    with RosSandbox() as sandbox:
        sandbox.run('olive_srvcli', 'temp_server')
        sandbox.command([sys.executable, __file__, '--echo-server'], label='echo')
        context = Context()
        rclpy.init(context=context, domain_id=sandbox.domain_id)
        try:
            ours, base = interleaved(context, ['temp_conversion', 'echo'], args.calls)
            long = {name: long_run(context, 'echo', args.long_calls, wait)
                    for name, wait in (('spin_until_future_complete', spin_until_complete),
                                       ('spin_once loop', spin_once_loop))}
        finally:
            rclpy.try_shutdown(context=context)
    print(f'{args.calls} TempConv calls per server, the two called in turn (ms)')
    print(f'{"server":<24}{"p50":>8}{"p99":>8}{"mean":>8}')
    for name, latencies in (('temp_server', ours), ('echo (rclpy baseline)', base)):
        print(f'{name:<24}{percentile(latencies, 0.5):>8.3f}{percentile(latencies, 0.99):>8.3f}'
              f'{statistics.fmean(latencies):>8.3f}')
    print(f'ratio temp_server/echo: p50 {percentile(ours, 0.5) / percentile(base, 0.5):.2f}x, '
          f'p99 {percentile(ours, 0.99) / percentile(base, 0.99):.2f}x')
    print(f'long run: {args.long_calls} sequential calls to echo, mean of the first and last {window} (ms)')
    worst = 0.0
    for name, latencies in long.items():
        first, last = statistics.fmean(latencies[:window]), statistics.fmean(latencies[-window:])
        worst = max(worst, last / first)
        print(f'{name:<28} first {first:7.3f}  last {last:7.3f}  ratio last/first {last / first:.2f}x')
    verdict = 'met' if worst <= TARGET else 'MISSED'
    print(f'long run: worst ratio {worst:.2f}x (target <= {TARGET}x): {verdict}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
