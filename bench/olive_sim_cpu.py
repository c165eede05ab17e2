"""CPU cost of the simulated Owl Kit, the camera's highest frame rate and the servo's real-time margin.

Everything is measured in one run, against baselines measured in the same run:
- CPU (% of one core, from /proc utime+stime over --seconds) of each module alone at its defaults,
  and of the whole kit (IMU, servo pan, servo tilt, camera eye with the launch file's parameters),
  against a bare rclpy node publishing a JointState at 100 Hz (the cheapest "module").
- Highest camera frame rate at 640x480: render + JPEG encode in this process (no ROS), with the
  head moving and still, and what a best-effort subscriber receives from camera_sim asked for 240 fps.
- Servo physics: time of each fixed step of the model (p50/p99) against its 1 ms period.
- The modules' own web pages: the kit without pages (web_port 0), with pages no browser watches
  (the default), and with a page client watching every module's System Status (and the IMU's and
  camera's Debug GUI), the client's own CPU not counted, nor any time before it hears from every page.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import os
import socket
import sys
import threading
import time
from typing import TYPE_CHECKING

import rclpy
from measure import cpu_seconds
from olive_kit.description import CAMERA_TOPIC, OWL_KIT, KitModule, page_host
from olive_sim.camera_render import CameraRenderer
from olive_sim.servo_model import PidGains, ServoSim
from owl_common.processes import RosProcess, RosSandbox
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import CompressedImage, JointState

if TYPE_CHECKING:
    import aiohttp


def baseline_node() -> None:
    """The baseline: a bare rclpy node publishing a one-joint JointState at 100 Hz."""
    rclpy.init()
    node = Node('bench_baseline')
    publisher = node.create_publisher(JointState, 'baseline/joint', 10)
    node.create_timer(0.01, lambda: publisher.publish(JointState(name=['j'], position=[0.0])))
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        rclpy.try_shutdown()


def cpu_percent(processes: list[RosProcess], warmup: float, seconds: float,
                watcher: PageWatcher | None = None) -> float:
    """Combined CPU of the processes over `seconds`, after `warmup`, in % of one core.

    With a watcher, also not before it watches every page.
    """
    time.sleep(warmup)
    if watcher is not None and not watcher.watching.wait(60):
        raise SystemExit('the page client had not heard from every module page after 60 s')
    before = sum(cpu_seconds(p.pid) for p in processes)
    started = time.monotonic()
    time.sleep(seconds)
    used = sum(cpu_seconds(p.pid) for p in processes) - before
    for process in processes:
        if not process.running():
            raise SystemExit(f'{process.label} died:\n{process.output}')
    return 100.0 * used / (time.monotonic() - started)


def module_args(parameters: dict) -> list[str]:
    """The `--ros-args -p name:=value ...` arguments that start a module with these parameters."""
    args = ['--ros-args']
    for name, value in parameters.items():
        args += ['-p', f'{name}:={value}']
    return args


def measure_cpu(args: argparse.Namespace) -> dict[str, float]:
    """CPU (% of one core) by case: the baseline node, each module alone, and the whole kit three ways.

    The kit runs with its web pages, without them (web_port 0), and with every page watched by a
    PageWatcher; each case in a ROS sandbox of its own.
    """
    results = {}
    singles: dict[str, list[str]] = {'imu_sim': [], 'servo_sim': [], 'camera_sim': []}
    with RosSandbox() as sandbox:
        baseline = sandbox.command([sys.executable, __file__, '--baseline-node'], label='baseline')
        results['baseline (rclpy JointState 100 Hz)'] = cpu_percent([baseline], args.warmup, args.seconds)
    for executable, extra in singles.items():
        with RosSandbox() as sandbox:
            process = sandbox.run('olive_sim', executable, *extra)
            results[executable] = cpu_percent([process], args.warmup, args.seconds)
    for name, port, watch in (('whole kit (4 processes)', free_port(), False),
                              ('whole kit, no web pages (web_port 0)', 0, False),
                              ('whole kit, every page watched', free_port(), True)):
        with RosSandbox() as sandbox:
            kit = [sandbox.run('olive_sim', m.executable, *module_args({**m.parameters, 'web_port': port}))
                   for m in OWL_KIT]
            watcher = PageWatcher(port) if watch else None
            try:
                results[name] = cpu_percent(kit, args.warmup, args.seconds, watcher)
            finally:
                if watcher is not None:
                    updates = watcher.stop()
                    print(f'  (the page client received {updates} updates in that case)')
    return results


def free_port() -> int:
    """A TCP port free on 127.0.0.1 when asked, for the kit's web pages (not reserved: it may be taken)."""
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


class PageWatcher:
    """A browser's share of the work, without a browser: a WebSocket client on every module page.

    Each module page's WebSocket is subscribed to System Status, and the IMU's and camera's to their
    Debug GUI orientation.
    """

    def __init__(self, port: int) -> None:
        import aiohttp
        self.aiohttp = aiohttp
        self.port = port
        self.updates = 0
        self.heard_from = 0  # module pages that sent their first update
        self.watching = threading.Event()  # set once every one has
        self.loop = asyncio.new_event_loop()
        # made here (Python 3.10+ binds it to the loop that first waits on it): stop() always has it
        self.stopping = asyncio.Event()
        self.thread = threading.Thread(target=self.loop.run_until_complete, args=(self._watch(),),
                                       daemon=True)
        self.thread.start()

    async def _watch(self) -> None:
        async with self.aiohttp.ClientSession() as session:
            tasks = [asyncio.create_task(self._module(session, m)) for m in OWL_KIT]
            await self.stopping.wait()
            for task in tasks:
                task.cancel()
            await asyncio.gather(*tasks, return_exceptions=True)

    async def _module(self, session: aiohttp.ClientSession, module: KitModule) -> None:
        url = f'ws://{page_host(module.address)}:{self.port}/ws'
        deadline = time.monotonic() + 60
        while True:
            try:
                websocket = await session.ws_connect(url)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                await asyncio.sleep(0.1)  # the page is not up yet
        channels = ['system'] + (['orientation'] if module.module_type in ('imu', 'camera') else [])
        async with websocket:  # closed when stop() cancels this task
            for index, channel in enumerate(channels):
                await websocket.send_str(json.dumps({'type': 'subscribe', 'id': index, 'channel': channel}))
            first = True
            async for _ in websocket:
                self.updates += 1
                if first:  # the page answers a subscription with an update at once
                    first = False
                    self.heard_from += 1
                    if self.heard_from == len(OWL_KIT):
                        self.watching.set()

    def stop(self) -> int:
        """Stop watching; the number of updates the pages sent in all, for the bench's report."""
        self.loop.call_soon_threadsafe(self.stopping.set)
        self.thread.join(10)
        return self.updates


def camera_render_rate(frames: int, moving: bool) -> float:
    """Frames per second of render + JPEG encode at 640x480 in this process (no ROS), head moving or not."""
    renderer = CameraRenderer(640, 480)
    renderer.jpeg(0.0, 0.0, 'warm-up')
    started = time.perf_counter()
    for index in range(frames):
        # A moving head: pan and tilt change every frame, so the tilt lookup is rebuilt too. A
        # still head (the kit at rest) changes only the caption.
        step = index if moving else 0
        renderer.jpeg(0.3 * math.sin(step / 10), 0.2 * math.cos(step / 15), f'#{index}')
    return frames / (time.perf_counter() - started)


def camera_delivered_rate(seconds: float) -> float:
    """Frames per second a best-effort subscriber receives from camera_sim asked for 240 fps.

    Counted over `seconds` after the first frames arrive; 0.0 if fewer than two came in that time.
    """
    with RosSandbox() as sandbox:
        sandbox.run('olive_sim', 'camera_sim', '--ros-args', '-p', 'fps:=240.0')
        context = Context()
        rclpy.init(context=context, domain_id=sandbox.domain_id)
        executor = SingleThreadedExecutor(context=context)
        try:
            node = Node('bench_camera_viewer', context=context)
            stamps: list[float] = []
            node.create_subscription(CompressedImage, CAMERA_TOPIC,
                                     lambda m: stamps.append(time.monotonic()), qos_profile_sensor_data)
            executor.add_node(node)
            deadline = time.monotonic() + 30
            while not stamps and time.monotonic() < deadline:
                executor.spin_once(timeout_sec=0.1)
            first = len(stamps)
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                executor.spin_once(timeout_sec=0.1)
            window = stamps[first:]
            return (len(window) - 1) / (window[-1] - window[0]) if len(window) > 1 else 0.0
        finally:
            executor.shutdown()  # before its context (Jazzy's Executor.__del__ would print a traceback)
            rclpy.try_shutdown(context=context)


def servo_step_times(steps: int) -> list[float]:
    """Durations in us, sorted, of `steps` servo physics steps following the course's 0 / 1.57 rad goals."""
    sim = ServoSim(gains=PidGains(5.0, 10.0, 0.3))
    sim.enable_torque(True)
    durations = []
    for index in range(steps):
        if index % 3000 == 0:
            sim.goal_position = 1.57 if sim.goal_position == 0.0 else 0.0  # the course's script
        started = time.perf_counter_ns()
        sim.step()
        durations.append((time.perf_counter_ns() - started) / 1000.0)
    return sorted(durations)


def main() -> int:
    """Run every measurement and print its table (exit code 0); with --baseline-node, be that node."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--seconds', type=float, default=10.0, help='CPU measuring window per case')
    parser.add_argument('--warmup', type=float, default=4.0, help='wait after start before measuring')
    parser.add_argument('--camera-seconds', type=float, default=5.0,
                        help='window of the 240 fps camera delivery measurement')
    parser.add_argument('--baseline-node', action='store_true', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if not (args.seconds > 0 and args.warmup >= 0 and args.camera_seconds > 0):
        parser.error('--seconds and --camera-seconds must be positive, --warmup not negative')
    if args.baseline_node:
        baseline_node()
        return 0

    cpu = measure_cpu(args)
    base = cpu['baseline (rclpy JointState 100 Hz)']
    print(f'CPU over {args.seconds:g} s at default settings (% of one core; {os.cpu_count()} cores)')
    print(f'{"process":<38}{"CPU %":>8}{"x baseline":>12}')
    for name, value in cpu.items():
        print(f'{name:<38}{value:>8.1f}{value / base if base else float("nan"):>12.2f}')
    kit = cpu['whole kit (4 processes)']
    print(f'whole kit: {kit:.1f} % of one core (target < 25 %: {"met" if kit < 25 else "NOT met"})')
    print(f"web pages with no browser: {kit - cpu['whole kit, no web pages (web_port 0)']:+.1f} points; "
          f"every page watched: {cpu['whole kit, every page watched'] - kit:+.1f} points more")

    moving = camera_render_rate(120, moving=True)
    still = camera_render_rate(300, moving=False)
    delivered = camera_delivered_rate(args.camera_seconds)
    print('\nCamera at 640x480 (jpeg quality 80)')
    print(f'render + encode in process (moving head): {moving:.1f} fps')
    print(f'render + encode in process (still head):  {still:.1f} fps')
    print(f'camera_sim asked for 240 fps, received:   {delivered:.1f} fps '
          f'({delivered / 30.0:.2f}x the default 30 fps)')

    durations = servo_step_times(30000)
    p50 = durations[len(durations) // 2]
    p99 = durations[int(0.99 * len(durations))]
    period = 1e6 / 1000.0
    print('\nServo physics step (1 kHz, position PID at 500 Hz, course step goals)')
    print(f'p50 {p50:.1f} us, p99 {p99:.1f} us, max {durations[-1]:.1f} us against a {period:.0f} us period: '
          f'p99 uses {100 * p99 / period:.1f} % of the period (margin {period / p99:.0f}x)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
