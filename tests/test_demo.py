"""`owl demo` (make demo): the chapter 4 robot live over real DDS, in readable lines, stopped cleanly."""

import os
import re
import subprocess
from pathlib import Path

import pytest
from olive_kit.description import SERVO_RANGES
from olive_sim.scene_model import BALL_START, BallPath
from owl_cli.demo import robot as demo
from owl_web.pages import stop_front_door

STATUS = re.compile(
    r'IMU roll +[+-]\d+° pitch +[+-]\d+° yaw +[+-]\d+° \| pan goal ([+-]\d\.\d\d) at ([+-]\d\.\d\d) rad \| '
    r'tilt goal ([+-]\d\.\d\d) at ([+-]\d\.\d\d) rad \| camera +(\d+\.\d) fps \| turtle \(')


def run_demo(*args: str, timeout: float = 150,
             pages_dir: Path | None = None) -> subprocess.CompletedProcess:
    """The demo as on a machine without a display (CI's case, whatever the developer's desktop has).

    Its pages join a front door of pages_dir's, on any free port (the demo uses the user's own).
    """
    env = {k: v for k, v in os.environ.items() if k not in ('DISPLAY', 'WAYLAND_DISPLAY')}
    if pages_dir is not None:
        env.update({'OWL_PAGES_DIR': str(pages_dir), 'OWL_FRONT_DOOR_PORT': '0', 'OWL_FRONT_DOOR': 'on'})
    try:
        return subprocess.run(['owl', 'demo', *args], capture_output=True, text=True, timeout=timeout,
                              env=env, check=False)
    finally:
        if pages_dir is not None:
            stop_front_door(pages_dir)


@pytest.mark.whole_kit
def test_demo_runs_the_robot_reports_it_and_stops_every_node_cleanly(tmp_path):
    # Four reports, one more than the test needs: a loaded machine that holds one up still leaves three.
    result = run_demo('--seconds', '6', '--report-every', '1.5', pages_dir=tmp_path / 'pages')
    assert result.returncode == 0, result.stdout + result.stderr
    statuses = [s for line in result.stdout.splitlines() if (s := STATUS.search(line))]
    assert len(statuses) >= 3, result.stdout
    # The head follows the IMU: the servos reach their goals, and the camera streams.
    pan_goal, pan_at, tilt_goal, tilt_at, fps = map(float, statuses[-1].groups())
    assert abs(pan_goal - pan_at) < 0.3, statuses[-1].group(0)
    assert abs(tilt_goal - tilt_at) < 0.3, statuses[-1].group(0)
    assert fps > 10, statuses[-1].group(0)
    assert "display_camera says:" in result.stdout, result.stdout
    assert 'no display' in result.stdout, result.stdout
    # one address for every page, the front door's, printed before the status lines: the robot view and
    # the turtle's window (owl windows) are there (tests/test_front_door.py opens them)
    address = re.search(r"^== pages: open http://127\.0\.0\.1:(\d+)/ in a browser: the robot view .*, "
                        r"windows \(the TurtleSim window and display_camera's, .*\), each module's own page",
                        result.stdout, re.M)
    assert address, result.stdout
    assert len(re.findall(r'http://', result.stdout)) == 1, result.stdout
    assert result.stdout.index(address.group(0)) < result.stdout.index('== running')
    assert 'every node stopped cleanly' in result.stdout
    assert 'Traceback' not in result.stdout + result.stderr


def test_the_tracking_demos_ball_stays_where_the_pan_servo_can_centre_it():
    assert f'ball_swing:={demo.BALL_SWING}' in demo.KIT_WITH_BALL
    assert f'ball_speed:={demo.BALL_SPEED}' in demo.KIT_WITH_BALL
    path = BallPath(*BALL_START, speed=demo.BALL_SPEED, swing=demo.BALL_SWING)
    low, high = SERVO_RANGES['pan']
    margin = 0.3  # rad: the head turns beyond the ball by its lag, and the picture has edges
    assert all(low + margin <= path.at(t)[0] <= high - margin for t in range(0, 600))
    # it moves: in a 20 s demo it goes most of the way to one side and back
    assert max(path.at(t)[0] for t in range(20)) - BALL_START[0] > 0.8 * demo.BALL_SWING


TRACKING = re.compile(r'ball +([+-]\d+\.\d) % right, +([+-]\d+\.\d) % down of the middle \| pan goal')


# whole_kit: the head's lag grows with the pipeline's latency, camera to servo. Beside two other tests
# on 2 cores a run's mean was 6.1 %, with a 1 s gap in the demo's reports.
@pytest.mark.whole_kit
def test_the_tracking_demo_keeps_the_ball_in_the_middle_and_says_how_far_off_it_is(tmp_path):
    result = run_demo('--project', 'tracking', '--seconds', '6', '--report-every', '1',
                      pages_dir=tmp_path / 'pages')
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'track_object: the head keeps the ball in the middle of the picture' in result.stdout
    assert 'a red ball swinging 52° to either side in front of the robot' in result.stdout
    assert 'drag the red ball elsewhere and the head follows it' in result.stdout  # not the IMU demo's hint
    offsets = [tuple(map(float, m.groups()))
               for line in result.stdout.splitlines() if (m := TRACKING.search(line))]
    assert len(offsets) >= 4, result.stdout
    # A ball going round lags a little behind the head (section 4.6's figure is the mean; a busy
    # machine's slower loop once showed 5.8 % on one line).
    assert sum(abs(right) for right, _ in offsets) / len(offsets) < 5, result.stdout
    assert all(abs(right) < 10 and abs(down) < 10 for right, down in offsets), result.stdout
    assert 'every node stopped cleanly' in result.stdout
    assert 'Traceback' not in result.stdout + result.stderr


def test_demo_refuses_a_bad_duration_or_project_in_one_line():
    bad = (['--seconds', '-3'], ['--seconds', 'soon'], ['--report-every', '0'], ['--project', 'juggling'])
    for args in bad:
        result = run_demo(*args, timeout=30)
        assert result.returncode == 2, args
        assert 'Traceback' not in result.stderr
        assert result.stderr.strip().splitlines()[-1].startswith('usage:') is False
        assert 'error:' in result.stderr.strip().splitlines()[-1], result.stderr
