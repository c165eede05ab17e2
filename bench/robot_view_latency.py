"""Latency from a drag of the IMU in the robot view to the pan servo moving, against a DDS baseline.

The baseline is measured in the same run: the same turn of the simulated IMU published straight on
DDS.

One private ROS domain runs robot_view.launch.py (the kit with its IMU in command mode, and
robot_view) and the course's imu_control_robot (the head points where the IMU points). Chromium
(Debian's, through Playwright, as the browser tests) opens the page.

- page: the mouse holds the IMU block and moves it 20 px (0.2 rad of yaw), the next time left,
  then right, ...; timed from that one mouse move (Playwright's call) to the first pan `joint`
  message 0.01 rad away from where it was: browser, WebSocket, robot_view, DDS to imu_sim, imu_sim
  turning, imu_control_robot, servo_sim. Also split where the page's hold_imu reaches DDS.
- direct (baseline): this process publishes the same 0.2 rad turns on imu_sim's true_orientation:
  everything after robot_view.
- round trip (what a student sees, issue 57's item 7): in the page, from the pointer event of that
  mouse move to the first frame whose shown IMU yaw has turned half of the way: page, WebSocket,
  robot_view, DDS, imu_sim, DDS, robot_view, WebSocket, page. "Turned": SHOWN rad, beyond the IMU's
  noise (imu_sim turns toward a commanded orientation at most 3 rad/s, as a hand does, so the whole
  0.2 rad takes 67 ms more). Its baseline: this process publishing the turn on true_orientation until
  the first IMU message turned as much arrives here (imu_sim's turn-around).

Prints p50, p95, p99 and max of each in ms and the ratios page / direct: what the browser path adds.
"""

from __future__ import annotations

import argparse
import math
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from geometry_msgs.msg import Quaternion
from measure import percentile
from olive_kit.description import IMU_NAMESPACE, IMU_TOPIC, joint_topic, node_name
from owl_common.probe import Probe
from owl_common.processes import RosProcess, RosSandbox
from sensor_msgs.msg import Imu, JointState

TESTS = Path(__file__).resolve().parents[1] / 'tests'
sys.path.insert(0, str(TESTS))  # the browser tests' Chromium set-up: one piece of code for it
from web_harness import ON_KIT_STATE, Browser, chromium_missing, free_port  # noqa: E402

TRUE_ORIENTATION = f"/{node_name('imu', IMU_NAMESPACE)}/true_orientation"
PAN_JOINT = joint_topic('pan')
URL_LINE = r'robot_view: open (http://127\.0\.0\.1:\d+/) in a browser'
PIXELS = 20  # one drag; the page turns the IMU 0.01 rad a pixel
TURN = PIXELS * 0.01
MOVED = 0.01  # rad: the pan servo has moved
SHOWN = 0.01  # rad: the IMU has turned (its orientation noise is 0.002 rad)
STARTUP_TIMEOUT = 60.0
SAMPLE_TIMEOUT = 10.0


class Timings:
    """Arrival times (time.monotonic) of the pan joint's positions and of true_orientation messages.

    Waits are woken by the arrivals (no polling): the bench's own CPU is the kit's and Chromium's
    to lose on a 2-core machine.
    """

    def __init__(self, probe: Probe) -> None:
        self.joints: list[tuple[float, float]] = []
        self.commands: list[float] = []
        self.yaws: list[tuple[float, float]] = []  # the IMU's (arrival, yaw)
        self._arrived = threading.Condition()
        probe.node.create_subscription(JointState, PAN_JOINT, self._on_joint, 10)
        probe.node.create_subscription(Imu, IMU_TOPIC, self._on_imu, 10)
        probe.node.create_subscription(
            Quaternion, TRUE_ORIENTATION, lambda _: self.commands.append(time.monotonic()), 10)

    def _on_joint(self, joint: JointState) -> None:
        with self._arrived:
            self.joints.append((time.monotonic(), joint.position[0]))
            self._arrived.notify_all()

    def _on_imu(self, imu: Imu) -> None:
        q = imu.orientation
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))
        with self._arrived:
            self.yaws.append((time.monotonic(), yaw))
            self._arrived.notify_all()

    def _first(self, arrivals: list[tuple[float, float]], started: float, since: int,
               away_from: float, by: float, what: str) -> float:
        """Time of the first of arrivals[since:] after `started` whose value is `by` away from `away_from`."""
        index = since
        found: list[float] = []

        def arrived() -> bool:
            nonlocal index
            while index < len(arrivals):
                when, value = arrivals[index]
                index += 1
                if when > started and abs(value - away_from) > by:
                    found.append(when)
                    return True
            return False

        with self._arrived:
            if not self._arrived.wait_for(arrived, SAMPLE_TIMEOUT):
                raise SystemExit(f'{what} within {SAMPLE_TIMEOUT} s')
        return found[0]

    def wait_for_yaw(self, started: float, from_yaw: float) -> float:
        """Time of the first IMU message after `started` whose yaw turned SHOWN rad from `from_yaw`."""
        return self._first(self.yaws, started, max(0, len(self.yaws) - 50), from_yaw, SHOWN,
                           'the IMU did not turn')

    def wait_for_move(self, started: float, from_position: float) -> float:
        """Time of the first joint message after `started` MOVED away from `from_position`."""
        # the list only grows; what came before is older
        return self._first(self.joints, started, max(0, len(self.joints) - 5), from_position, MOVED,
                           'the pan servo did not move')

    def settle(self, seconds: float) -> float:
        """Wait, then the pan's latest position."""
        time.sleep(seconds)
        return self.joints[-1][1]


def yaw_quaternion(yaw: float) -> Quaternion:
    """The level orientation turned by `yaw` rad about z, as published on imu_sim's true_orientation."""
    return Quaternion(x=0.0, y=0.0, z=math.sin(yaw / 2), w=math.cos(yaw / 2))


# In the page: from the next pointermove's event to the first frame (requestAnimationFrame's time)
# whose shown IMU (window.robotView.imu, the readout's) has turned SHOWN rad of yaw.
# Also when the turned IMU arrived in the page (the kit state setting robotView.imu): the split between
# the way there and back and the wait for a frame.
ROUND_TRIP = f"""() => {{
  const yaw = ([x, y, z, w]) => Math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z));
  const view = window.robotView;
  const before = yaw(view.imu);
  const trip = {{ moved: null, arrived: null, shown: null }};
  window.roundTrip = trip;
  ({ON_KIT_STATE})(view, (value) => {{
    if (trip.moved !== null && trip.arrived === null && value && Math.abs(yaw(value) - before) > {SHOWN}) {{
      trip.arrived = performance.now();
    }}
  }});
  const once = {{ capture: true, once: true }};
  addEventListener('pointermove', (event) => {{ trip.moved = event.timeStamp; }}, once);
  const frame = (time) => {{
    if (trip.moved !== null && Math.abs(yaw(view.imu) - before) > {SHOWN}) trip.shown = time;
    else requestAnimationFrame(frame);
  }};
  requestAnimationFrame(frame);
}}"""


def measure_page(page, timings: Timings, samples: int,
                 pause: float) -> tuple[list[float], list[float], list[float], list[float]]:
    """Ms from the mouse move: to the pan moving, hold_imu on DDS, the turn shown, the turn in the page."""
    to_moving, to_command, round_trips, arrivals = [], [], [], []
    for sample in range(samples):
        start_position = timings.settle(pause)
        grip = page.evaluate('window.robotView.imuOnPage()')
        page.mouse.move(grip['x'], grip['y'])
        page.mouse.down()
        page.evaluate(ROUND_TRIP)
        commands_before = len(timings.commands)
        started = time.monotonic()
        page.mouse.move(grip['x'] + (PIXELS if sample % 2 == 0 else -PIXELS), grip['y'])
        page.mouse.up()
        moved = timings.wait_for_move(started, start_position)
        to_moving.append((moved - started) * 1000)
        if len(timings.commands) > commands_before:  # the probe heard robot_view's command
            to_command.append((timings.commands[commands_before] - started) * 1000)
        page.wait_for_function('() => window.roundTrip.shown !== null', timeout=SAMPLE_TIMEOUT * 1000)
        trip = page.evaluate('window.roundTrip')
        round_trips.append(trip['shown'] - trip['moved'])
        if trip['arrived'] is not None:
            arrivals.append(trip['arrived'] - trip['moved'])
    return to_moving, to_command, round_trips, arrivals


def measure_direct(probe: Probe, timings: Timings, samples: int,
                   pause: float) -> tuple[list[float], list[float]]:
    """Ms from publishing a 0.2 rad turn on true_orientation to the pan moving, and to the IMU turned."""
    publisher = probe.node.create_publisher(Quaternion, TRUE_ORIENTATION, 10)
    publisher.publish(yaw_quaternion(0.0))
    to_moving, to_imu = [], []
    for sample in range(samples):
        start_position = timings.settle(pause)
        start_yaw = timings.yaws[-1][1]
        started = time.monotonic()
        publisher.publish(yaw_quaternion(TURN if sample % 2 == 0 else 0.0))
        to_imu.append((timings.wait_for_yaw(started, start_yaw) - started) * 1000)
        to_moving.append((timings.wait_for_move(started, start_position) - started) * 1000)
    return to_moving, to_imu


def line(what: str, values: list[float]) -> str:
    """One printed row: p50, p95, p99 and max of values (ms), and how many samples there were."""
    return (f'{what:<46} p50 {percentile(values, 0.5):6.1f} ms   p95 {percentile(values, 0.95):6.1f} ms   '
            f'p99 {percentile(values, 0.99):6.1f} ms   max {max(values):6.1f} ms   ({len(values)} samples)')


def stop_in_turn(robot: RosProcess, launch: RosProcess) -> None:
    """Stop imu_control_robot, then the launch.

    The robot disables the servos' torque as it stops, which takes the servos still running: stopped
    side by side (as the sandbox stops what runs), it waits 3 s for a dead servo_sim, then is killed.
    """
    robot.stop(3.0)
    launch.stop(3.0)


def main() -> int:
    """Time both paths in a private domain and print them; exit code 0, or 1 when Chromium is missing."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--samples', type=int, default=100, help='turns per path (default 100)')
    parser.add_argument('--pause', type=float, default=0.5, help='s the servo gets to settle between turns')
    args = parser.parse_args()
    if args.samples < 1 or not args.pause > 0:
        parser.error('--samples must be at least 1 and --pause positive')
    missing = chromium_missing()
    if missing:
        print(f'robot_view_latency: cannot run: {missing}', file=sys.stderr)
        return 1
    with RosSandbox() as sandbox:
        launch = sandbox.command(
            ['ros2', 'launch', 'robot_view', 'robot_view.launch.py', f'port:={free_port()}'],
            label='robot_view.launch')
        robot = sandbox.run('olive_servo', 'imu_control_robot')
        # The probe and Chromium start while the nodes do.
        probe = Probe(sandbox.domain_id, 'latency_bench')
        timings = Timings(probe)
        browser = Browser()
        try:
            base = launch.wait_for(URL_LINE, STARTUP_TIMEOUT)[0].group(1)
            robot.wait_for(r'torque enabled: pan, tilt', STARTUP_TIMEOUT)
            page = browser.new_page()
            page.goto(base)
            page.wait_for_function('() => window.robotView.pan !== null && window.robotView.imu !== null',
                                   timeout=STARTUP_TIMEOUT * 1000)
            # the baseline first, then the page: both start from a level IMU and the head at rest
            direct, direct_imu = measure_direct(probe, timings, args.samples, args.pause)
            page.click('#level')
            to_moving, to_command, round_trips, arrivals = measure_page(
                page, timings, args.samples, args.pause)
        finally:
            with ThreadPoolExecutor(1) as pool:  # the nodes stop while Chromium closes
                pool.submit(stop_in_turn, robot, launch)
                browser.close()
            probe.close()
    print(line('page: drag -> pan servo moving', to_moving))
    if to_command:
        print(line('page: drag -> hold_imu on DDS', to_command))
    print(line('direct: true_orientation -> pan moving', direct))
    print(f'ratio page / direct: p50 {percentile(to_moving, 0.5) / percentile(direct, 0.5):.2f}x, '
          f'p99 {percentile(to_moving, 0.99) / percentile(direct, 0.99):.2f}x')
    print(line('page: mouse move -> the turn shown (a frame)', round_trips))
    if arrivals:
        print(line('  of which: mouse move -> turned IMU in the page', arrivals))
    print(line('direct: true_orientation -> IMU turned', direct_imu))
    trip, baseline = round_trips, direct_imu
    print(f'ratio round trip / direct: p50 {percentile(trip, 0.5) / percentile(baseline, 0.5):.2f}x, '
          f'p95 {percentile(trip, 0.95) / percentile(baseline, 0.95):.2f}x '
          '(the target: a round trip p95 under 50 ms on a quiet machine)')
    return 0


if __name__ == '__main__':
    sys.exit(main())
