"""How smooth the robot view stays while the IMU is dragged, live plots on, against plots paused.

One private ROS domain runs robot_view.launch.py (the kit with its IMU in command mode, its camera
at 30 frames/s, and robot_view) and the course's imu_control_robot, so the head, the plots and the
camera all move while the block is held. Headless Chromium (Debian's, through Playwright, as the
browser tests) opens the page at 1280 x 800; the mouse holds the IMU block and sweeps it left and
right, one move every MOVE_EVERY s, for --seconds. Measured in the page, from Chromium's own clocks:

- input delay: from a pointermove event's timestamp (when Chromium took the mouse move) to the
  page's first listener running (capture phase): how long input waits behind other work;
- frames/s: requestAnimationFrame callbacks a second while dragging;
- long tasks: main-thread tasks over 50 ms (PerformanceObserver 'longtask'), count and longest;
- the camera label's frame rate at the end.

Two runs in the same invocation: live (plots drawing, the page as a student has it), then the
baseline: the same drag with the plots paused. Targets (issue 28): live input delay p95 < 50 ms and
at least 30 frames/s. Prints each run's numbers and the ratio live / paused.
"""

from __future__ import annotations

import argparse
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

from measure import percentile
from owl_common.processes import RosProcess, RosSandbox

TESTS = Path(__file__).resolve().parents[1] / 'tests'
sys.path.insert(0, str(TESTS))  # the browser tests' Chromium set-up: one piece of code for it
from web_harness import Browser, chromium_missing, free_port  # noqa: E402

URL_LINE = r'robot_view: open (http://127\.0\.0\.1:\d+/) in a browser'
STARTUP_TIMEOUT = 60.0
MOVE_EVERY = 0.016  # s between two mouse moves: a 60 Hz mouse
SWEEP = 120  # px each way
TARGET_P95_MS = 50.0
TARGET_FPS = 30.0

# Installed before the page's own scripts, so its listener runs first (capture, on window).
RECORDER = """
window.smooth = { recording: false, delays: [], frames: 0, longTasks: [] };
addEventListener('pointermove', (event) => {
  if (window.smooth.recording) window.smooth.delays.push(performance.now() - event.timeStamp);
}, { capture: true });
(function count() {
  if (window.smooth.recording) window.smooth.frames += 1;
  requestAnimationFrame(count);
})();
new PerformanceObserver((list) => {
  if (!window.smooth.recording) return;
  for (const entry of list.getEntries()) window.smooth.longTasks.push(entry.duration);
}).observe({ type: 'longtask' });
"""


def drag_for(page: Any, seconds: float) -> dict[str, Any]:
    """Hold the IMU block and sweep it for `seconds`; what the page recorded meanwhile."""
    grip = page.evaluate('window.robotView.imuOnPage()')
    page.mouse.move(grip['x'], grip['y'])
    page.mouse.down()
    page.evaluate('() => { Object.assign(window.smooth, {recording: true, delays: [], frames: 0, '
                  'longTasks: []}); }')
    started = time.monotonic()
    step = 0
    while (elapsed := time.monotonic() - started) < seconds:
        phase = (step % (2 * SWEEP // 4)) * 4
        offset = phase if phase <= SWEEP else 2 * SWEEP - phase
        page.mouse.move(grip['x'] + offset - SWEEP / 2, grip['y'])
        step += 1
        time.sleep(max(0.0, started + step * MOVE_EVERY - time.monotonic()))
    recorded = page.evaluate('() => { window.smooth.recording = false; return window.smooth; }')
    page.mouse.up()
    recorded['seconds'] = elapsed
    recorded['moves'] = step
    recorded['camera_fps'] = page.evaluate('window.robotView.fps')
    return recorded


def summary(recorded: dict[str, Any]) -> dict[str, float]:
    """p50/p95/max input delay (ms), frames/s and long tasks of one run."""
    delays = recorded['delays'] or [float('nan')]
    long_tasks = recorded['longTasks']
    return {'p50': percentile(delays, 0.5), 'p95': percentile(delays, 0.95), 'max': max(delays),
            'fps': recorded['frames'] / recorded['seconds'], 'long': len(long_tasks),
            'longest': max(long_tasks, default=0.0), 'events': len(recorded['delays']),
            'camera_fps': recorded['camera_fps']}


def line(what: str, numbers: dict[str, float]) -> str:
    """One printed row of a run."""
    return (f"{what:<14} input delay p50 {numbers['p50']:6.1f} ms  p95 {numbers['p95']:6.1f} ms  "
            f"max {numbers['max']:6.1f} ms ({numbers['events']:.0f} moves)  {numbers['fps']:5.1f} frames/s  "
            f"long tasks {numbers['long']:.0f} (longest {numbers['longest']:.0f} ms)  "
            f"camera label {numbers['camera_fps']:.1f} fps")


def stop_in_turn(robot: RosProcess, launch: RosProcess) -> None:
    """Stop imu_control_robot, then the launch.

    The robot disables the servos' torque as it stops, which takes the servos still running: stopped
    side by side (as the sandbox stops what runs), it waits 3 s for a dead servo_sim, then is killed.
    """
    robot.stop(3.0)
    launch.stop(3.0)


def main() -> int:
    """Drag with plots live, then paused; print both and the targets. Exit code 1 without Chromium."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--seconds', type=float, default=10.0, help='s of dragging per run (default 10)')
    args = parser.parse_args()
    if not args.seconds > 0:
        parser.error('--seconds must be positive')
    missing = chromium_missing()
    if missing:
        print(f'robot_view_smoothness: cannot run: {missing}', file=sys.stderr)
        return 1
    with RosSandbox() as sandbox:
        launch = sandbox.command(
            ['ros2', 'launch', 'robot_view', 'robot_view.launch.py', f'port:={free_port()}'],
            label='robot_view.launch')
        robot = sandbox.run('olive_servo', 'imu_control_robot')
        browser = Browser()  # Chromium starts while the nodes do
        try:
            base = launch.wait_for(URL_LINE, STARTUP_TIMEOUT)[0].group(1)
            robot.wait_for(r'torque enabled: pan, tilt', STARTUP_TIMEOUT)
            page = browser.new_page()
            page.add_init_script(RECORDER)
            page.goto(base)
            page.wait_for_function('() => window.robotView.imu !== null && window.robotView.frames > 30 '
                                   '&& window.robotView.plots.batches > 20', timeout=STARTUP_TIMEOUT * 1000)
            live = summary(drag_for(page, args.seconds))
            page.click('#pause')
            paused = summary(drag_for(page, args.seconds))
        finally:
            with ThreadPoolExecutor(1) as pool:  # the nodes stop while Chromium closes
                pool.submit(stop_in_turn, robot, launch)
                browser.close()
    print(line('plots live', live))
    print(line('plots paused', paused))
    print(f"ratio live / paused: input delay p95 {live['p95'] / paused['p95']:.2f}x, "
          f"frames/s {live['fps'] / paused['fps']:.2f}x")
    met = live['p95'] < TARGET_P95_MS and live['fps'] >= TARGET_FPS
    print(f"targets (live): input delay p95 < {TARGET_P95_MS:.0f} ms, >= {TARGET_FPS:.0f} frames/s: "
          f"{'met' if met else 'NOT met'}")
    return 0


if __name__ == '__main__':
    sys.exit(main())
