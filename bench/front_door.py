"""What the front door costs: latency per request and per WebSocket message, and its CPU while streaming.

Baseline in the same run: the same page at its own port. A page server (owl_web's, in this process,
no ROS) joins a front door of a private pages folder, started as users get it (its own process):

- request: a small JSON GET on one kept-alive connection, direct and through the front door, in turns;
- message: a WebSocket command and its answer ("done"), direct and through the front door, in turns.

Then the front door's CPU while it carries the robot view's stream: robot_view.launch.py (the whole
kit) in a private ROS domain, its page open in Chromium through the front door (the camera at 30
frames/s, the model, the plots), the front door's own process time over --seconds, as a share of one
core (the target: at most 2 %), beside robot_view's for scale.

Prints p50 and p95 of each path in ms, what the front door adds and the ratio to the baseline.
"""

from __future__ import annotations

import argparse
import asyncio
import http.client
import json
import os
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from urllib.parse import urlsplit

import aiohttp
from measure import cpu_seconds, percentile
from owl_common.processes import RosSandbox
from owl_web import pages
from owl_web.server import WebServer

TESTS = Path(__file__).resolve().parents[1] / 'tests'
sys.path.insert(0, str(TESTS))  # the browser tests' Chromium set-up: one piece of code for it
from web_harness import Browser, chromium_missing  # noqa: E402

PAGE = {'mount': 'bench', 'title': 'bench', 'start': 'python bench/front_door.py'}
STARTUP_TIMEOUT = 60.0
WARM_UP = 3.0  # s of streaming before the CPU is counted (--warm-up)


def timed_requests(urls: list[str], count: int) -> dict[str, list[float]]:
    """Ms per GET of each url, on one kept-alive connection each, the urls in turns."""
    connections = {url: http.client.HTTPConnection(urlsplit(url).netloc, timeout=10) for url in urls}
    times: dict[str, list[float]] = {url: [] for url in urls}
    try:
        for _ in range(count):
            for url in urls:
                connection = connections[url]
                started = time.perf_counter()
                connection.request('GET', urlsplit(url).path)
                answer = connection.getresponse()
                answer.read()
                times[url].append((time.perf_counter() - started) * 1000)
                if answer.status != 200:
                    raise SystemExit(f'front_door: {url} answered {answer.status}')
    finally:
        for connection in connections.values():
            connection.close()
    return times


async def timed_messages(urls: list[str], count: int) -> dict[str, list[float]]:
    """Ms from a command sent on each url's WebSocket to its answer, the urls in turns."""
    times: dict[str, list[float]] = {url: [] for url in urls}
    async with aiohttp.ClientSession() as session:
        sockets = {url: await session.ws_connect(url) for url in urls}
        for n in range(count):
            for url, socket_ in sockets.items():
                started = time.perf_counter()
                await socket_.send_str(json.dumps({'type': 'command', 'id': n, 'name': 'echo'}))
                answer = json.loads((await socket_.receive(10)).data)
                times[url].append((time.perf_counter() - started) * 1000)
                if answer.get('type') != 'done':
                    raise SystemExit(f'front_door: {url} answered {answer}')
        for socket_ in sockets.values():
            await socket_.close()
    return times


def row(what: str, values: list[float]) -> str:
    """One printed line: p50 and p95 of values in ms."""
    return f'{what:<34} p50 {percentile(values, 0.5):6.2f} ms   p95 {percentile(values, 0.95):6.2f} ms'


def latency(requests: int, messages: int) -> None:
    """Print the request and message latencies, direct and through the front door."""
    with tempfile.TemporaryDirectory() as folder:
        os.environ.update({'OWL_PAGES_DIR': folder, 'OWL_FRONT_DOOR_PORT': '0', 'OWL_FRONT_DOOR': 'on'})
        static = Path(folder) / 'static'
        static.mkdir()
        (static / 'index.html').write_text('<!DOCTYPE html><title>bench</title>')
        server = WebServer('bench', static, log=print)
        server.route('GET', '/api/ping', lambda _: {'pong': True})
        server.command('echo', lambda _: None)
        server.join_front_door(PAGE, [PAGE])
        server.start()
        try:
            direct, door = server.url, server.address
            asked = timed_requests([direct + 'api/ping', door + 'api/ping'], requests)
            sent = asyncio.run(timed_messages([direct + 'ws', door + 'ws'], messages))
        finally:
            server.stop()
            pages.stop_front_door(Path(folder))
    for what, times, count in (('request', asked, requests), ('WebSocket message', sent, messages)):
        own, through = times.values()
        print(row(f'{what}: own port', own))
        print(row(f'{what}: front door', through))
        print(f'{what}: the front door adds {percentile(through, 0.5) - percentile(own, 0.5):.2f} ms at p50; '
              f'ratio front door / own port p50 {percentile(through, 0.5) / percentile(own, 0.5):.2f}x, '
              f'p95 {percentile(through, 0.95) / percentile(own, 0.95):.2f}x ({count} each)')


def streaming_cpu(seconds: float, warm_up: float) -> int:
    """Print the front door's CPU while the robot view streams through it; 1 when Chromium is missing.

    Counted over `seconds`, after `warm_up` s of streaming.
    """
    missing = chromium_missing()
    if missing:
        print(f'front_door: cannot run the streaming part: {missing}', file=sys.stderr)
        return 1
    with RosSandbox() as sandbox:
        sandbox.env.update({'OWL_FRONT_DOOR': 'on', 'OWL_FRONT_DOOR_PORT': '0'})
        launch = sandbox.command(['ros2', 'launch', 'robot_view', 'robot_view.launch.py', 'port:=0'],
                                 label='robot_view.launch')
        browser = Browser()  # Chromium starts while the launch does
        try:
            opened = launch.wait_for(r'robot_view: open (http://127\.0\.0\.1:\d+/robot-view/) in a browser',
                                     STARTUP_TIMEOUT)[0].group(1)
            assert sandbox.pages_dir is not None
            door = pages.front_door_record(Path(sandbox.pages_dir))
            view = pages.registered(Path(sandbox.pages_dir))['robot-view']
            if door is None:
                raise SystemExit('front_door: no front door runs')
            page = browser.new_page()
            page.goto(opened)
            page.wait_for_function('() => window.robotView.frames > 10', timeout=STARTUP_TIMEOUT * 1000)
            time.sleep(warm_up)
            frames, cpu, view_cpu = (page.evaluate('window.robotView.frames'), cpu_seconds(door.pid),
                                     cpu_seconds(view.pid))
            started = time.monotonic()
            time.sleep(seconds)
            elapsed = time.monotonic() - started
            frames = page.evaluate('window.robotView.frames') - frames
            cpu, view_cpu = cpu_seconds(door.pid) - cpu, cpu_seconds(view.pid) - view_cpu
        finally:
            with ThreadPoolExecutor(1) as pool:  # the launch stops while Chromium closes
                pool.submit(launch.stop, 3.0)
                browser.close()
    print(f'streaming through the front door for {elapsed:.1f} s: {frames / elapsed:.1f} camera frames/s '
          f'on the page; the front door used {100 * cpu / elapsed:.2f} % of a core (target <= 2 %), '
          f'robot_view {100 * view_cpu / elapsed:.1f} %; ratio front door / robot_view '
          f'{cpu / view_cpu if view_cpu else float("nan"):.2f}x')
    return 0


def main() -> int:
    """Run both parts; exit code 0, or 1 when the streaming part cannot run."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--requests', type=int, default=1000, help='GETs per path (default 1000)')
    parser.add_argument('--messages', type=int, default=1000,
                        help='WebSocket commands per path (default 1000)')
    parser.add_argument('--seconds', type=float, default=20.0, help='s of streaming counted (default 20)')
    parser.add_argument('--warm-up', type=float, default=WARM_UP,
                        help=f's of streaming before the counting starts (default {WARM_UP:g})')
    args = parser.parse_args()
    if args.requests < 1 or args.messages < 1 or not args.seconds > 0 or args.warm_up < 0:
        parser.error('--requests and --messages must be at least 1, --seconds positive, '
                     '--warm-up not negative')
    latency(args.requests, args.messages)
    return streaming_cpu(args.seconds, args.warm_up)


if __name__ == '__main__':
    sys.exit(main())
