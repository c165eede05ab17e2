"""Service round-trip latency: temp_server against a minimal rclpy echo service, same run.

Both servers run as separate processes in a private ROS domain; this process is the client and
makes N sequential TempConv calls to each. Prints p50/p99 per server and their ratio
(temp_server / echo): the cost of our server code and logging over bare rclpy.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import rclpy
from measure import percentile
from olive_interfaces.srv import TempConv
from owl_common.processes import RosSandbox
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node


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


def measure(node: Node, executor: SingleThreadedExecutor, service: str, calls: int) -> list[float]:
    """Latency in ms of each of `calls` sequential calls (after 20 warm-up calls)."""
    client = node.create_client(TempConv, service)
    if not client.wait_for_service(timeout_sec=30.0):
        raise SystemExit(f'service {service} did not come up')
    latencies = []
    for index in range(calls + 20):
        started = time.perf_counter()
        future = client.call_async(TempConv.Request(temp_c=float(index)))
        executor.spin_until_future_complete(future, timeout_sec=10.0)
        if not future.done():
            raise SystemExit(f'call {index} to {service} timed out')
        if index >= 20:
            latencies.append((time.perf_counter() - started) * 1000.0)
    return latencies


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--calls', type=int, default=1000)
    parser.add_argument('--echo-server', action='store_true', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.echo_server:
        echo_server()
        return 0
    with RosSandbox() as sandbox:
        sandbox.run('olive_srvcli', 'temp_server')
        sandbox.command([sys.executable, __file__, '--echo-server'], label='echo')
        context = Context()
        rclpy.init(context=context, domain_id=sandbox.domain_id)
        executor = SingleThreadedExecutor(context=context)
        try:
            node = Node('bench_client', context=context)
            executor.add_node(node)
            results = {
                'temp_server': measure(node, executor, 'temp_conversion', args.calls),
                'echo (rclpy baseline)': measure(node, executor, 'echo', args.calls),
            }
        finally:
            executor.shutdown()  # before its context (Jazzy's Executor.__del__ would print a traceback)
            rclpy.try_shutdown(context=context)
    print(f'{args.calls} sequential TempConv calls per server (ms)')
    print(f'{"server":<24}{"p50":>8}{"p99":>8}{"mean":>8}')
    for name, latencies in results.items():
        print(f'{name:<24}{percentile(latencies, 0.5):>8.3f}{percentile(latencies, 0.99):>8.3f}'
              f'{statistics.fmean(latencies):>8.3f}')
    ours, base = results.values()
    print(f'ratio temp_server/echo: p50 {percentile(ours, 0.5) / percentile(base, 0.5):.2f}x, '
          f'p99 {percentile(ours, 0.99) / percentile(base, 0.99):.2f}x')
    return 0


if __name__ == '__main__':
    sys.exit(main())
