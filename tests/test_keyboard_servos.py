"""keyboard_servos over real DDS against olive_sim's servos, through its real window and its seam.

Arrow keys pressed in its real window under Xvfb, and key events through the headless seam
(src/tools/owl_venv_hooks/owl_gui_hook.py); which arrow turns which servo which way, goals within
the bounds, torque on before the first goal and off after Ctrl-C, the speed and bound parameters
and their bad values.
"""

import signal
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

import pytest
from diagnostic_msgs.msg import DiagnosticStatus
from ros_harness import wait_for_messages, wait_until
from servo_helpers import BOUNDS, assert_clean_servo, collect, start_servo, torque_enabled

SERVOS = ('pan', 'tilt')
SPEED = 3.0  # rad/s: the goal crosses the pan range in about a second
HEADLESS = {'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1'}
NO_DISPLAY_LINE = 'keyboard_servos: no display'


X_KEY_NAMES = {'left': 'Left', 'right': 'Right', 'up': 'Up', 'down': 'Down'}


class XKeys:
    """Arrow keys held in keyboard_servos' window on a virtual X display (xdotool)."""

    def __init__(self, x_display, window: str) -> None:
        self.x_display = x_display
        self.window = window
        x_display.xdotool('windowactivate', '--sync', window)

    def down(self, key: str) -> None:
        self.x_display.xdotool('keydown', '--window', self.window, X_KEY_NAMES[key])

    def up(self, key: str) -> None:
        self.x_display.xdotool('keyup', '--window', self.window, X_KEY_NAMES[key])


class SeamKeys:
    """Key events written to the headless seam's keys file (OWL_WINDOWS_DIR)."""

    def __init__(self, keys_file: Path) -> None:
        wait_until(keys_file.exists, 30, f'the seam keys file {keys_file}')
        self.keys_file = keys_file

    def send(self, line: str) -> None:
        with self.keys_file.open('a') as keys:
            keys.write(line + '\n')

    def down(self, key: str) -> None:
        self.send(f'down {key}')

    def up(self, key: str) -> None:
        self.send(f'up {key}')


class Head:
    """Both servos' goals, joint states and diagnostics as the probe receives them."""

    def __init__(self, ros) -> None:
        self.goals = {name: collect(ros, name, 'goal/position') for name in SERVOS}
        self.joints = {name: collect(ros, name, 'joint') for name in SERVOS}
        self.diagnostics = {name: collect(ros, name, 'joint/diagnostics') for name in SERVOS}

    def goal(self, name: str) -> float:
        return self.goals[name][-1].data

    def joint(self, name: str) -> float:
        return self.joints[name][-1].position[0] if self.joints[name] else float('nan')

    def wait_goal(self, name: str, test: Callable[[float], bool], what: str, timeout: float = 10.0) -> None:
        wait_until(lambda: test(self.goal(name)), timeout, f'{name} goal {what} (last {self.goal(name):.4f})')

    def wait_joint(self, name: str, test: Callable[[float], bool], what: str, timeout: float = 20.0) -> None:
        wait_until(lambda: test(self.joint(name)), timeout,
                   f'{name} joint {what} (last {self.joint(name):.4f})')

    def assert_goals_within_bounds(self) -> None:
        for name, (low, high) in BOUNDS.items():
            outside = [g.data for g in self.goals[name] if not low - 1e-6 <= g.data <= high + 1e-6]
            assert not outside, (name, outside[:5])


def start_keyboard_servos(ros, *params: str, env: dict[str, str | None]):
    """keyboard_servos first, then the servos: a goal before the torque is on would reach them."""
    node = ros.run('olive_servo', 'keyboard_servos', '--ros-args', '-p', f'speed:={SPEED}', *params, env=env)
    node.wait_for(r'waiting for service /olive/servo/pan/setTorqueEnable', timeout=30)
    servos = {name: start_servo(ros, name) for name in SERVOS}
    node.wait_for(r'torque enabled: pan, tilt', timeout=30)
    return node, servos


def drive_the_head(head: Head, keys) -> None:
    """Each arrow moves its servo the documented way, only while held, and never past a bound."""
    wait_for_messages(head.goals['pan'], 20, timeout=20, what='pan goals')
    wait_for_messages(head.goals['tilt'], 20, timeout=20, what='tilt goals')
    assert head.goal('pan') == 0.0  # the head starts at its centre
    assert head.goal('tilt') == 0.0
    pan_upper = BOUNDS['pan'][1]
    tilt_lower = BOUNDS['tilt'][0]

    # Left: the head turns left, positive pan (REP 103), up to the bound and no further.
    start = len(head.goals['pan'])
    keys.down('left')
    head.wait_goal('pan', lambda g: g == pytest.approx(pan_upper, abs=1e-6), 'at its upper bound')
    wait_for_messages(head.goals['pan'], len(head.goals['pan']) + 20,
                      what='pan goals, Left held past the bound')
    head.wait_joint('pan', lambda p: p > pan_upper - 0.1, 'turned left to its bound')
    keys.up('left')
    pan_goals = [g.data for g in head.goals['pan'][start:]]
    assert pan_goals == sorted(pan_goals)  # only ever to the left while Left is held
    assert all(g.data == 0.0 for g in head.goals['tilt'])  # Left moves the pan servo only
    time.sleep(0.3)
    released = len(head.goals['pan'])
    wait_for_messages(head.goals['pan'], released + 20, what='pan goals after Left was released')
    after = [g.data for g in head.goals['pan'][released:]]
    assert after
    assert all(g == pytest.approx(pan_upper, abs=1e-6) for g in after)  # released: it stays

    # Right: back to the right, negative pan.
    keys.down('right')
    head.wait_goal('pan', lambda g: g < -0.5, 'below -0.5 rad')
    keys.up('right')
    head.wait_joint('pan', lambda p: p < -0.3, 'turned right')

    # Up: the camera looks up, negative tilt, up to the bound and no further.
    start = len(head.goals['tilt'])
    keys.down('up')
    head.wait_goal('tilt', lambda g: g == pytest.approx(tilt_lower, abs=1e-6), 'at its lower bound')
    wait_for_messages(head.goals['tilt'], len(head.goals['tilt']) + 20,
                      what='tilt goals, Up held past the bound')
    head.wait_joint('tilt', lambda p: p < tilt_lower + 0.15, 'looking up to its bound')
    keys.up('up')
    tilt_goals = [g.data for g in head.goals['tilt'][start:]]
    assert tilt_goals == sorted(tilt_goals, reverse=True)

    # Down: the camera looks down, positive tilt.
    keys.down('down')
    head.wait_goal('tilt', lambda g: g > 0.3, 'above 0.3 rad')
    keys.up('down')
    head.wait_joint('tilt', lambda p: p > 0.1, 'looking down')
    head.assert_goals_within_bounds()


def torque_off_since(diagnostics: list[DiagnosticStatus], count: int) -> bool:
    return len(diagnostics) > count and not torque_enabled(diagnostics)


def stop_and_check_the_torque(node, servos, head: Head) -> None:
    """Ctrl-C: exit code 0, the torque of both servos off, and they never saw a goal too early."""
    node.stop_cleanly(timeout=10)
    assert 'Traceback' not in node.output, node.output
    for name, servo in servos.items():
        assert f'torque disabled: {name}' in node.output
        servo.wait_for(r'\]: torque disabled$', timeout=10)
        count = len(head.diagnostics[name])
        wait_until(partial(torque_off_since, head.diagnostics[name], count), 10,
                   f'{name} torque_enabled false')
        assert_clean_servo(servo)


def test_arrow_keys_in_its_window_move_the_head_the_documented_way_within_the_bounds(ros, x_display):
    head = Head(ros)
    node, servos = start_keyboard_servos(ros, env=x_display.env())
    window = x_display.wait_for_window(pid=node.pid)
    drive_the_head(head, XKeys(x_display, window))
    assert NO_DISPLAY_LINE not in node.output
    stop_and_check_the_torque(node, servos, head)


def test_without_a_display_it_says_so_in_one_line_and_seam_key_events_move_the_head(ros, tmp_path):
    head = Head(ros)
    windows = tmp_path / 'windows'
    node, servos = start_keyboard_servos(ros, env={**HEADLESS, 'OWL_WINDOWS_DIR': str(windows)})
    seam = windows / f'keyboard_servos-{node.pid}'
    drive_the_head(head, SeamKeys(seam / 'keys'))
    assert len([line for line in node.lines if NO_DISPLAY_LINE in line]) == 1, node.output
    assert not [line for line in node.lines if 'ALSA' in line or 'XDG' in line], node.output
    assert (seam / 'pygame.png').stat().st_size > 0  # what the window shows, for the browser lab
    stop_and_check_the_torque(node, servos, head)


def test_closing_its_window_stops_it_as_ctrl_c_does(ros, x_display):
    head = Head(ros)
    node, servos = start_keyboard_servos(ros, env=x_display.env())
    window = x_display.wait_for_window(pid=node.pid)
    wait_for_messages(head.goals['pan'], 20, timeout=20, what='pan goals')
    x_display.close_window(window)
    assert node.wait(15) == 0, node.output
    assert 'Traceback' not in node.output, node.output
    for name, servo in servos.items():
        assert f'torque disabled: {name}' in node.output
        servo.wait_for(r'\]: torque disabled$', timeout=10)
        assert_clean_servo(servo)


def test_ctrl_c_while_it_waits_for_the_servos_exits_cleanly(ros):
    node = ros.run('olive_servo', 'keyboard_servos', env=HEADLESS)
    node.wait_for(r'waiting for service /olive/servo/pan/setTorqueEnable', timeout=30)
    node.stop_cleanly(timeout=10)
    assert 'Traceback' not in node.output, node.output
    assert 'torque disabled' not in node.output, node.output


def test_sigterm_while_it_waits_for_the_servos_ends_it(ros):
    # SDL would turn SIGTERM into a window-close event that nothing reads while the node waits.
    node = ros.run('olive_servo', 'keyboard_servos', env=HEADLESS)
    node.wait_for(r'waiting for service /olive/servo/pan/setTorqueEnable', timeout=30)
    node.send_signal(signal.SIGTERM)
    assert node.wait(5) == -signal.SIGTERM


@pytest.mark.parametrize(('args', 'message'), [
    (['-p', 'speed:=fast'], "'speed' to 'fast' of type 'STRING', expecting type 'DOUBLE'"),
    (['-p', 'speed:=2'], "'speed' to '2' of type 'INTEGER', expecting type 'DOUBLE'"),
    (['-p', 'speed:=0.0'], 'Parameter speed out of range'),
    (['-p', 'speed:=7.5'], 'Parameter speed out of range'),
    (['-p', 'pan_min:=1.0', '-p', 'pan_max:=0.5'], 'pan_min (1.0) must be less than pan_max (0.5)'),
    (['-p', 'tilt_min:=0.9'], 'tilt_min (0.9) must be less than tilt_max (0.9)'),
    (['-p', 'tilt_max:=4.0'], 'Parameter tilt_max out of range'),
])
def test_bad_startup_parameters_end_with_one_line_and_code_2(ros, args, message):
    node = ros.run('olive_servo', 'keyboard_servos', '--ros-args', *args, env=HEADLESS)
    assert node.wait(30) == 2
    assert len(node.lines) == 1, node.output
    assert node.lines[0].startswith('keyboard_servos: error: '), node.output
    assert message in node.output


def test_speed_and_bounds_change_at_runtime_and_bad_values_are_refused_with_a_reason(ros, tmp_path):
    head = Head(ros)
    windows = tmp_path / 'windows'
    node, servos = start_keyboard_servos(ros, env={**HEADLESS, 'OWL_WINDOWS_DIR': str(windows)})
    keys = SeamKeys(windows / f'keyboard_servos-{node.pid}' / 'keys')
    probe = ros.probe
    for values, reason in (({'speed': 10.0}, 'out of range'), ({'speed': 0.0}, 'out of range'),
                           ({'speed': 'fast'}, 'type'), ({'speed': 2}, 'type'),
                           ({'pan_min': 2.0}, 'pan_min (2.0) must be less than pan_max (1.5708)'),
                           ({'tilt_max': -1.5}, 'tilt_min (-1.3) must be less than tilt_max (-1.5)'),
                           ({'pan_max': 3.5}, 'out of range'), ({'tilt_min': 'low'}, 'type')):
        [result] = probe.set_parameters('/keyboard_servos', **values)
        assert not result.successful, (values, result.reason)
        assert reason in result.reason, (values, result.reason)
    names = ('speed', 'pan_min', 'pan_max', 'tilt_min', 'tilt_max')
    assert probe.get_parameters('/keyboard_servos', *names) == [SPEED, -1.5708, 1.5708, -1.3, 0.9]

    # A slower speed: the goal moves at 0.5 rad/s while the key is held.
    assert all(r.successful for r in probe.set_parameters('/keyboard_servos', speed=0.5))
    keys.down('left')
    head.wait_goal('pan', lambda g: g > 0.05, 'moving left')
    first_time, first_goal = time.monotonic(), head.goal('pan')
    time.sleep(1.5)
    rate = (head.goal('pan') - first_goal) / (time.monotonic() - first_time)
    keys.up('left')
    assert 0.35 < rate < 0.65, rate

    # Narrower bounds: the goal comes back within them with no key held, and stays there.
    assert all(r.successful for r in probe.set_parameters('/keyboard_servos', pan_max=0.3, tilt_max=0.2))
    head.wait_goal('pan', lambda g: g == pytest.approx(0.3), 'brought back to 0.3 rad')
    keys.down('down')
    head.wait_goal('tilt', lambda g: g == pytest.approx(0.2), 'held at 0.2 rad')
    time.sleep(0.5)
    keys.up('down')
    assert max(g.data for g in head.goals['tilt']) == pytest.approx(0.2)
    stop_and_check_the_torque(node, servos, head)
