"""owl check's logic without ROS: catalogue, workspace and build decision, judgements, report."""

import http.server
import json
import os
import sys
import threading
import time
from pathlib import Path
from typing import ClassVar

import pytest
from owl_cli.check import catalogue
from owl_cli.check import command as check
from owl_cli.check import criteria as judge
from owl_cli.check import workspace as ws
from owl_cli.check.report import (
    CHECK_DONE,
    RESULT_PREFIX,
    Criterion,
    ExerciseResult,
    exit_code,
    read_latest,
    record_latest,
    results_file,
    share_latest,
    summary_table,
    to_json,
)
from owl_cli.main import main

# -- catalogue -------------------------------------------------------------------------------------


def test_every_exercise_has_a_check_or_a_reason_and_a_unique_id():
    assert [e.id for e in catalogue.EXERCISES] == list(catalogue.BY_ID)
    for exercise in catalogue.EXERCISES:
        assert (exercise.check is None) == bool(exercise.not_checked), exercise.id


def test_the_plugins_come_in_the_courses_section_order():
    sections = [catalogue.section_order(e.section.split()[0].rstrip(','))[:2] for e in catalogue.EXERCISES]
    assert sections == sorted(sections)
    assert catalogue.EXERCISES[0].id == 'test_package'
    assert catalogue.EXERCISES[-1].id == 'gesture_control_launch'


def test_two_plugins_that_declare_one_id_are_refused(monkeypatch):
    twin = catalogue.Section()
    twin.by_hand('imu_turtle', '4.3.2', 'olive_imu', 'again', 'a second declaration')

    class Plugin:
        def __init__(self, name: str, section: catalogue.Section) -> None:
            self.name, self.section = name, section

        def load(self) -> catalogue.Section:
            return self.section

    first = catalogue.Section()
    first.by_hand('imu_turtle', '4.3.2', 'olive_imu', 'first', 'a declaration')
    monkeypatch.setattr(catalogue, 'entry_points', lambda group: [Plugin('4.3', first), Plugin('9.9', twin)])
    with pytest.raises(ValueError, match='more than one plug-in declares imu_turtle'):
        catalogue.load_exercises()


def test_no_check_module_is_longer_than_400_lines():
    folder = Path(catalogue.__file__).parent  # owl_cli/check/, its exercises included
    modules = sorted(folder.rglob('*.py'))
    assert folder / 'exercises' / 'section_4_4_1.py' in modules
    for module in modules:
        assert len(module.read_text().splitlines()) <= 400, module


def test_the_catalogue_covers_sections_3_4_to_4_7_with_every_extra():
    sections = {e.section.split()[0].rstrip(',') for e in catalogue.EXERCISES}
    course = {'3.4', '3.5', '3.6', '3.6.1', '3.7.1', '3.7.2', '3.8', '3.9'}
    course |= {'4.3', '4.3.2', '4.4', '4.4.1', '4.5', '4.6', '4.7'}
    assert course <= sections | {s.rsplit('.', 1)[0] for s in sections}
    # The "+" items: 3 of 4.3.2, 2 of 4.4, 2 of 4.4.1, 1 of 4.5; 2 of 4.6 and 2 of 4.7 (our text).
    extras = [e.id for e in catalogue.EXERCISES if e.extra]
    assert len(extras) == 12, extras
    assert all(catalogue.BY_ID[i].checkable for i in extras)


def test_the_ids_are_the_course_executable_names():
    for name in (
        'random_number_publisher',
        'temp_server',
        'imu_turtle',
        'control_servo',
        'pid_testing',
        'keyboard_servos',
        'imu_control_robot',
        'display_camera',
    ):
        assert catalogue.find(name) is not None, name


def test_an_unknown_id_names_the_closest_and_a_far_one_names_none():
    assert catalogue.closest('imu_turtel') == 'imu_turtle'
    assert catalogue.closest('display_cam') == 'display_camera'
    assert catalogue.closest('zzzz') is None
    assert catalogue.unknown_id_message('zzzz') == (
        "owl check: unknown exercise 'zzzz' ('owl check --list' lists them)"
    )


def test_the_listing_has_one_aligned_line_per_exercise():
    lines = catalogue.listing()
    assert len(lines) == len(catalogue.EXERCISES)
    width = max(len(e.id) for e in catalogue.EXERCISES) + 2
    for line, exercise in zip(lines, catalogue.EXERCISES, strict=True):
        assert line[:width].rstrip() == exercise.id
        assert line[width:].startswith(exercise.section + ' ')
        suffix = '' if exercise.checkable else ' [not checked: done by hand]'
        assert line.endswith(exercise.description + suffix)


# -- command line (no ROS: the bad inputs stop before any check runs) -------------------------------


def test_list_and_bad_input_exit_codes(capsys, tmp_path, monkeypatch):
    assert main(['check', '--list']) == 0
    assert 'imu_turtle' in capsys.readouterr().out
    assert main(['check', 'imu_turtel']) == 2
    assert "did you mean 'imu_turtle'" in capsys.readouterr().err
    assert main(['check']) == 2
    assert 'give exercise ids or --all' in capsys.readouterr().err
    assert main(['check', 'turtle_background']) == 2
    [line] = capsys.readouterr().err.strip().splitlines()
    assert line.startswith('owl check: turtle_background (section 3.7.1 exercise) is not checked: typed at')
    monkeypatch.chdir(tmp_path)
    assert main(['check', 'imu_turtle']) == 2
    [line] = capsys.readouterr().err.strip().splitlines()
    assert 'is not in a colcon workspace' in line


def test_help_exits_0(capsys):
    with pytest.raises(SystemExit) as stopped:
        main(['check', '-h'])
    assert stopped.value.code == 0
    assert '--all' in capsys.readouterr().out


# -- workspace -------------------------------------------------------------------------------------


def make_package(src, name, depends=(), build_type='ament_python'):
    folder = src / name
    folder.mkdir(parents=True)
    deps = ''.join(f'<depend>{d}</depend>' for d in depends)
    (folder / 'package.xml').write_text(
        f'<package format="3"><name>{name}</name>{deps}<export><build_type>{build_type}</build_type>'
        '</export></package>'
    )
    (folder / 'setup.py').write_text('')
    return folder


def test_the_workspace_is_found_from_inside_a_package_and_a_package_src_is_not_one(tmp_path):
    cmake = make_package(tmp_path / 'src', 'olive_interfaces', build_type='ament_cmake')
    (cmake / 'src').mkdir()
    (cmake / 'src' / 'main.cpp').write_text('')
    python = make_package(tmp_path / 'src', 'olive_imu')
    (python / 'olive_imu').mkdir()
    assert ws.find_workspace(python / 'olive_imu') == tmp_path.resolve()
    assert ws.find_workspace(cmake / 'src') == tmp_path.resolve()
    with pytest.raises(ws.WorkspaceError):
        ws.find_workspace(tmp_path / 'src' / 'olive_imu' / 'olive_imu' / '..' / '..' / '..' / '..')


def test_packages_dependencies_and_colcon_ignore(tmp_path):
    make_package(tmp_path / 'src', 'olive_interfaces', build_type='ament_cmake')
    make_package(tmp_path / 'src', 'olive_srvcli', depends=['rclpy', 'olive_interfaces'])
    ignored = make_package(tmp_path / 'src' / 'old', 'olive_imu')
    (ignored.parent / 'COLCON_IGNORE').write_text('')
    found = ws.packages(tmp_path)
    assert sorted(found) == ['olive_interfaces', 'olive_srvcli']
    assert found['olive_interfaces'].build_type == 'ament_cmake'
    assert sorted(ws.needed('olive_srvcli', found)) == ['olive_interfaces', 'olive_srvcli']


def test_a_package_is_stale_until_built_and_again_when_a_source_changes(tmp_path):
    package = make_package(tmp_path / 'src', 'olive_imu')
    found = ws.packages(tmp_path)
    assert ws.stale(tmp_path, ['olive_imu'], found) == ['olive_imu']
    marker = tmp_path / 'install' / 'olive_imu' / 'share' / 'colcon-core' / 'packages' / 'olive_imu'
    marker.parent.mkdir(parents=True)
    marker.write_text('')
    past = time.time() - 100
    for path in (package / 'package.xml', package / 'setup.py'):
        os.utime(path, (past, past))
    assert ws.stale(tmp_path, ['olive_imu'], found) == []
    (package / '__pycache__').mkdir()
    (package / '__pycache__' / 'x.pyc').write_text('')
    assert ws.stale(tmp_path, ['olive_imu'], found) == []
    (package / 'setup.py').write_text('# changed')
    os.utime(package / 'setup.py', (time.time() + 5, time.time() + 5))
    assert ws.stale(tmp_path, ['olive_imu'], found) == ['olive_imu']
    assert ws.build_command(['b', 'a']) == [
        'colcon',
        'build',
        '--symlink-install',
        '--packages-select',
        'a',
        'b',
    ]


def test_the_last_error_line_of_a_failed_build():
    output = '\n'.join(
        [
            'Starting >>> olive_imu',
            '--- stderr: olive_imu',
            '  File "setup.py", line 2',
            "SyntaxError: '(' was never closed",
            "Failed to run: Command '['python', '-c', 'import sys']' returned non-zero exit status 1.",
            '---',
            'Failed   <<< olive_imu [0.41s, exited with code 1]',
            'Summary: 0 packages finished [0.8s]',
            '  1 package failed: olive_imu',
        ]
    )
    assert ws.last_error_line(output) == "SyntaxError: '(' was never closed"
    assert ws.last_error_line('a\nsomething failed\nb') == 'something failed'


def test_the_3_6_exercise_executables_are_found_by_their_words():
    assert ws.find_executable(['currency_server', 'money_service'], 'currency', 'server') == 'currency_server'
    assert ws.find_executable(['euro_srv', 'euro_cli'], 'currency', 'server') == 'euro_srv'
    assert ws.find_executable(['euro_srv', 'euro_cli'], 'currency', 'client') == 'euro_cli'
    assert ws.find_executable(['fact_service', 'temp_server'], 'factorial', 'server') == 'fact_service'
    assert ws.find_executable(['temp_server', 'temp_client'], 'factorial', 'client') is None


def test_executables_of_an_isolated_install(tmp_path):
    folder = tmp_path / 'install' / 'olive_srvcli' / 'lib' / 'olive_srvcli'
    folder.mkdir(parents=True)
    for name, mode in (('factorial_server', 0o755), ('notes.txt', 0o644)):
        (folder / name).write_text('')
        (folder / name).chmod(mode)
    assert ws.executables(tmp_path, 'olive_srvcli') == ['factorial_server']
    assert ws.executables(tmp_path, 'missing') == []


DUMP = """/turtlesim:
  ros__parameters:
    background_b: 0
    background_g: 0
    background_r: 0
    qos_overrides:
      /parameter_events:
        publisher:
          depth: 1000
    use_sim_time: false
"""


def test_parameter_files_are_found_in_the_workspace_and_documents_and_read_flat(tmp_path):
    workspace, home = tmp_path / 'ws', tmp_path / 'home'
    (workspace / 'config').mkdir(parents=True)
    (workspace / 'config' / 'turtlesim.yaml').write_text(DUMP)
    (workspace / 'config' / 'other.yaml').write_text('a: 1\n')  # no ros__parameters
    (workspace / 'install').mkdir()
    (workspace / 'install' / 'copy.yaml').write_text(DUMP)  # colcon's copies do not count
    (home / 'Documents').mkdir(parents=True)
    (home / 'Documents' / 'turtlesim.yaml').write_text(DUMP)
    assert ws.parameter_files(workspace, home) == [
        workspace / 'config' / 'turtlesim.yaml',
        home / 'Documents' / 'turtlesim.yaml',
    ]
    nodes = ws.read_parameter_file(DUMP)
    assert nodes['/turtlesim']['background_r'] == 0
    assert nodes['/turtlesim']['qos_overrides./parameter_events.publisher.depth'] == 1000
    bad_files = (('[1, 2]', 'map node names'), ('x: 1', 'no ros__parameters'), ('a: [', 'not valid YAML'))
    for bad, reason in bad_files:
        with pytest.raises(ValueError, match=reason):
            ws.read_parameter_file(bad)


def test_the_layout_of_ros2_pkg_create(tmp_path):
    package = make_package(tmp_path / 'src', 'test_package')
    assert ws.package_layout_problems(package, 'test_package') == [
        'setup.cfg is missing',
        'resource/test_package is missing',
        'test_package/__init__.py is missing',
    ]
    (package / 'setup.cfg').write_text('')
    (package / 'resource').mkdir()
    (package / 'resource' / 'test_package').write_text('')
    (package / 'test_package').mkdir()
    (package / 'test_package' / '__init__.py').write_text('')
    assert ws.package_layout_problems(package, 'test_package') == []


# -- judgements ------------------------------------------------------------------------------------


def test_fahrenheit_names_the_listing_typo():
    assert judge.fahrenheit(100.0, 212.0).passed
    typo = judge.fahrenheit(100.0, 482.0)
    assert not typo.passed
    assert "listing's temp_c * 9 / 2" in typo.hint
    other = judge.fahrenheit(100.0, 300.0)
    assert not other.passed
    assert 'formula 1' in other.hint
    assert judge.kelvin(0.0, 273.15).passed
    assert not judge.kelvin(0.0, 273.0).passed


def test_the_turtle_judgement_tells_a_swap_from_a_sign_from_nothing():
    assert judge.turtle_response('pitch', 0.6, 0.0).passed
    assert judge.turtle_response('yaw', 0.0, 0.75).passed
    assert 'check the sign of pitch' in judge.turtle_response('pitch', -0.6, 0.0).hint
    assert 'check the sign of yaw' in judge.turtle_response('yaw', 0.0, -0.75).hint
    assert 'swapped' in judge.turtle_response('pitch', 0.0, 0.4).hint
    assert 'swapped' in judge.turtle_response('yaw', 0.5, 0.0).hint
    still = judge.turtle_response('pitch', 0.0, 0.0)
    assert not still.passed
    assert 'does not move when the IMU pitches forward' in still.hint
    assert judge.standing_still(0.01, -0.01).passed
    assert not judge.standing_still(0.3, 0.0).passed


def test_bounds_rate_and_sine():
    assert judge.bounded_goal('pan', [0.0, 1.0, 1.5708], -1.5708, 1.5708, 'Left is held').passed
    unbounded = judge.bounded_goal('pan', [0.0, 2.0, 4.8], -1.5708, 1.5708, 'Left is held')
    assert not unbounded.passed
    assert '+4.80' in unbounded.hint
    assert not judge.bounded_goal('pan', [], -1, 1, 'Left is held').passed
    assert judge.rate([0.0, 0.5, 1.0]) == 2.0
    assert judge.rate([1.0]) == 0.0
    assert judge.oscillates([0.0, 0.3, 0.6, 0.5])
    assert not judge.oscillates([0.0, 0.3, 0.6, 0.9])  # a ramp
    assert not judge.oscillates([0.0, 0.05, 0.0])  # too small
    assert judge.in_range('numbers', [1, 2, 3], 1, 3, 'x').passed
    assert not judge.in_range('numbers', [1, 50], 1, 3, 'x').passed


def test_numbers_in_a_range_are_decided_by_enough_of_them_or_by_one_outside():
    assert not judge.range_decided([], 1, 3, 4)
    assert not judge.range_decided([1, 3, 2], 1, 3, 4)  # within so far: more must come
    assert judge.range_decided([1, 3, 2, 1], 1, 3, 4)
    assert judge.range_decided([57], 1, 3, 4)  # fails in_range whatever follows
    assert not judge.in_range('numbers', [57, 1, 2, 3], 1, 3, 'x').passed
    assert judge.outside([0, 1, 3, 3.5], 1, 3) == [0, 3.5]


def test_lag_behind_a_moving_target_gives_the_benefit_of_the_doubt_about_its_start():
    # A ball leaving 0.3 rad at 0.2 rad/s some time between t=10.0 and t=10.1; measured at t=12.0
    # it is between 0.68 and 0.70 rad.
    assert judge.lag_behind_moving_target(0.69, 12.0, 0.3, 0.2, (10.0, 10.1)) == 0.0
    assert judge.lag_behind_moving_target(0.60, 12.0, 0.3, 0.2, (10.0, 10.1)) == pytest.approx(0.08)
    assert judge.lag_behind_moving_target(0.75, 12.0, 0.3, 0.2, (10.0, 10.1)) == pytest.approx(0.05)
    assert judge.lag_behind_moving_target(0.3, 9.0, 0.3, 0.0, (10.0, 10.0)) == 0.0  # a still target


def test_a_head_is_stopped_short_once_every_servo_stood_still_for_a_while_after_the_grace():
    from types import SimpleNamespace

    from owl_cli.check.exercises.section_4_6 import GRACE, STILL_FOR, stopped_short

    def states(*positions_at: tuple[float, float]) -> list:
        return [(t, SimpleNamespace(position=[p])) for t, p in positions_at]

    still = states(*((t / 10, 0.0) for t in range(100)))
    moving = states(*((t / 10, t / 1000) for t in range(100)))
    assert stopped_short({'pan': still, 'tilt': still}, since=0.0, now=9.9)
    assert not stopped_short({'pan': still, 'tilt': moving}, since=0.0, now=9.9)  # tilt still turns
    assert not stopped_short({'pan': still, 'tilt': still}, since=9.9 - GRACE + 0.1, now=9.9)  # too early
    assert not stopped_short({'pan': still, 'tilt': states()}, since=0.0, now=9.9)  # no joint states
    assert not stopped_short({'pan': still, 'tilt': still}, since=0.0, now=9.9 + STILL_FOR + 0.1)  # stale


def test_the_moving_ball_is_lost_once_one_joint_state_of_the_window_lags_too_far():
    from types import SimpleNamespace

    from owl_cli.check.exercises.section_4_6 import (
        BALL,
        FOLLOW_FROM,
        FOLLOW_UNTIL,
        FOLLOWING,
        MOVING_SPEED,
        fell_behind,
        lags_behind_moving_ball,
    )

    def state(measured: float, position: float) -> tuple[float, SimpleNamespace]:
        stamp = SimpleNamespace(sec=int(measured), nanosec=round(measured % 1 * 1e9))
        return 0.0, SimpleNamespace(header=SimpleNamespace(stamp=stamp), position=[position])

    left = (100.0, 100.0)
    seconds = [t / 10 + 0.05 for t in range(60)]  # after the ball set off, never on the window's edges
    on_the_ball = [state(100 + t, BALL[0] + MOVING_SPEED * t) for t in seconds]
    in_window = [t for t in seconds if FOLLOW_FROM <= t <= FOLLOW_UNTIL]
    assert lags_behind_moving_ball(on_the_ball, left) == pytest.approx([0.0] * len(in_window), abs=1e-6)
    assert not fell_behind(on_the_ball, left)
    late = state(100 + FOLLOW_FROM + 0.5, BALL[0] + MOVING_SPEED * (FOLLOW_FROM + 0.5) - 1.5 * FOLLOWING)
    assert fell_behind([*on_the_ball[:21], late], left)  # decided now: later states only add lags
    too_soon = state(100 + FOLLOW_FROM - 0.1, BALL[0])  # the head may still be catching up then
    assert not fell_behind([too_soon], left)
    assert not fell_behind([], left)


def test_held_keys_stop_when_each_servos_goals_stood_or_both_their_verdicts_are_known():
    from types import SimpleNamespace

    from owl_cli.check.exercises.section_4_4_1 import KEY_SWING, beyond_and_swung, goals_stopped

    def goals(*values_at: tuple[float, float]) -> list:
        return [(t, SimpleNamespace(data=v)) for t, v in values_at]

    at_limit = goals(*((t / 100, min(1.5708, t / 100)) for t in range(300)))
    assert goals_stopped(at_limit, 2.99)
    assert not goals_stopped(at_limit, 1.8)  # reached the limit 0.23 s ago
    assert not goals_stopped(goals(*((t / 100, t / 100) for t in range(300))), 2.99)  # still turning
    assert not goals_stopped(goals(*((t / 100, 0.0) for t in range(100))), 2.99)  # nothing lately
    assert goals_stopped(goals(*((t / 100, -1.3) for t in range(300))), 2.99)  # tilt, at a limit of its own
    assert beyond_and_swung([4.9, 4.8], [0.0, 2.0, 5.0], -1.5708, 1.5708)
    assert not beyond_and_swung([1.5, 1.4], [0.0, 2.0, 5.0], -1.5708, 1.5708)  # within so far
    assert not beyond_and_swung([1.6], [1.6 - KEY_SWING / 2], -1.5708, 1.5708)  # may swing more yet
    assert not beyond_and_swung([], [0.0, 5.0], -1.5708, 1.5708)


def test_a_held_keys_speed_is_measured_from_its_first_moving_goal():
    from types import SimpleNamespace

    from owl_cli.check.exercises.section_4_4_1 import held_long_enough, moving_goals

    # The key reached the node 0.4 s late, then the goal turned at 2 rad/s: the still goals before
    # must not dilute the slope (over a fixed window they halved it).
    goals = [(t / 50, SimpleNamespace(data=0.3 if t < 20 else 0.3 + 2.0 * (t - 19) / 50)) for t in range(50)]
    moving = moving_goals(goals, 0.3)
    assert moving[0][0] == pytest.approx(0.4)
    assert judge.slope(moving) == pytest.approx(2.0)
    assert held_long_enough(moving)
    assert not held_long_enough(moving[:10])  # 0.18 s of goals
    assert moving_goals(goals[:20], 0.3) == []  # the key not seen yet


def test_currency_and_factorial_answers():
    good = judge.currency_answers([116.0, 88.0, 93.0], [290.0, 220.0, 232.5])
    assert all(c.passed for c in good)
    one_rate = judge.currency_answers([116.0, 116.0, 116.0], [290.0, 290.0, 290.0])
    assert [c.passed for c in one_rate] == [True, True, False]
    fixed = judge.currency_answers([116.0, 88.0, 93.0], [116.0, 88.0, 93.0])
    assert not fixed[1].passed
    assert 'fixed rate' in fixed[1].hint
    assert not judge.currency_answers([116.0], [290.0])[0].passed
    assert judge.factorial_answer(5, [True, 120]).passed
    zero = judge.factorial_answer(0, [0])
    assert not zero.passed
    assert 'empty product' in zero.hint
    assert judge.factorial_answer(10, [3628800]).passed


def test_numbers_printed_and_the_slope_of_held_keys():
    assert judge.numbers_in('[INFO] [17.5] [c]: 100.0 Euros are 125.0 dollars, 75 pounds') == [
        17.5,
        100.0,
        125.0,
        75.0,
    ]
    assert judge.slope([(0.0, 0.0), (0.5, 0.5), (1.0, 1.0)]) == pytest.approx(1.0)
    assert judge.slope([(0.0, 1.0), (0.5, 0.0), (1.0, -1.0)]) == pytest.approx(2.0)
    assert judge.slope([(0.0, 1.0)]) == 0.0


# -- running the checks ----------------------------------------------------------------------------

# A stand-in for `python -m owl_cli.check.ros --wait ID`, which leaves marks in a folder: set up
# (its process started), begun, running (from begin to CHECK_DONE). how: ok, crash (before
# CHECK_DONE), crash_after_done (in its clean-up), hang.
FAKE_CHECK = f'''
import json, pathlib, sys, time
name, following, folder, how = sys.argv[1:5]
folder = pathlib.Path(folder)

def mark(what):
    (folder / f'{{name}}.{{what}}').touch()

def seen(other, what):  # whether the other check gets there within 10 s
    deadline = time.monotonic() + 10
    while not (folder / f'{{other}}.{{what}}').exists():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.01)
    return True

def criterion(text, passed):
    print({RESULT_PREFIX!r} + json.dumps({{'text': text, 'passed': passed}}), flush=True)

mark('set-up')
if not sys.stdin.readline():
    sys.exit(0)
alone = not list(folder.glob('*.running'))
mark('running')
mark('begun')
if how == 'hang':
    time.sleep(60)
criterion('no other check was running at its begin', alone)
if how != 'crash':
    criterion('the next one set up during this check', not following or seen(following, 'set-up'))
(folder / f'{{name}}.running').unlink()
if how == 'crash':
    raise RuntimeError('the check broke')
print({CHECK_DONE!r}, flush=True)
if following and not seen(following, 'begun'):
    raise RuntimeError('the next check began only after this clean-up')
if how == 'crash_after_done':
    raise RuntimeError('the clean-up broke')
'''


def fake_checks(monkeypatch, folder: Path, how: dict[str, str]) -> list[catalogue.Exercise]:
    """The exercises of how, each checked by FAKE_CHECK (check.start_check replaced)."""
    ids = list(how)

    def start(exercise: catalogue.Exercise, workspace: Path) -> check.CheckRun:
        following = ids[ids.index(exercise.id) + 1] if exercise.id != ids[-1] else ''
        command = [sys.executable, '-c', FAKE_CHECK, exercise.id, following, str(folder), how[exercise.id]]
        return check.CheckRun(exercise.id, command, dict(os.environ))

    monkeypatch.setattr(check, 'start_check', start)
    return [catalogue.Exercise(i, '0', 'pkg', 'fake') for i in ids]


def run_fakes(exercises: list[catalogue.Exercise], folder: Path) -> tuple[list[ExerciseResult], list[str]]:
    """check.run_checks over the fakes: the results and what was shown, in order."""
    shown: list[str] = []
    results = check.run_checks(
        exercises, folder, lambda c: None, lambda e: shown.append(e.id),
        lambda r: shown.append(f'{r.exercise}: {", ".join(c.text for c in r.criteria if not c.passed)}'))
    return results, shown


def test_a_check_sets_up_during_the_one_before_and_cleans_up_during_the_next(monkeypatch, tmp_path):
    exercises = fake_checks(monkeypatch, tmp_path, {'a': 'ok', 'b': 'ok', 'c': 'ok'})
    results, shown = run_fakes(exercises, tmp_path)
    assert shown == ['a', 'a: ', 'b', 'b: ', 'c', 'c: ']  # one check at a time, each shown whole
    for result in results:
        assert [(c.text, c.passed) for c in result.criteria] == [
            ('no other check was running at its begin', True),
            ('the next one set up during this check', True),
        ]


def test_a_check_that_crashes_in_or_after_its_criteria_fails_and_one_past_the_limit_is_stopped(
        monkeypatch, tmp_path):
    ended = 'the check ran to its end'
    exercises = fake_checks(monkeypatch, tmp_path, {'a': 'crash', 'b': 'crash_after_done', 'c': 'ok'})
    results, shown = run_fakes(exercises, tmp_path)
    assert shown[:2] == ['a', f'a: {ended}']  # the crash is in the result before it is shown
    assert [[c.text for c in r.criteria if not c.passed] for r in results] == [[ended], [ended], []]
    assert 'the clean-up broke' in results[1].criteria[-1].hint
    monkeypatch.setattr(check, 'HARD_LIMIT', 1.0)
    (tmp_path / 'hang').mkdir()
    [stopped], shown = run_fakes(fake_checks(monkeypatch, tmp_path / 'hang', {'d': 'hang'}), tmp_path)
    assert shown == ['d', 'd: the check ends within 1 s']
    assert 1.0 <= stopped.seconds < 10.0


def test_a_wait_looks_soon_at_first_then_every_50_ms():
    from itertools import islice

    from owl_cli.check.session import poll_intervals

    assert list(islice(poll_intervals(), 7)) == [0.005, 0.01, 0.02, 0.04, 0.05, 0.05, 0.05]


# -- report ----------------------------------------------------------------------------------------


def test_exit_codes_json_and_the_summary_table():
    good = ExerciseResult('imu_turtle', [Criterion('a', True)], 9.5)
    bad = ExerciseResult('temp_server', [Criterion('a', True), Criterion('b', False, 'hint')], 2.0)
    assert exit_code([good]) == 0
    assert exit_code([good, bad]) == 1
    assert exit_code([good, ExerciseResult('x', error='no package')]) == 2
    report = json.loads(to_json([good, bad], '/ws'))
    assert report['passed'] is False
    assert report['exercises'][1]['criteria'][1] == {
        'text': 'b',
        'passed': False,
        'hint': 'hint',
        'detail': '',
    }
    table = summary_table([good, bad])
    assert table[2].split() == ['imu_turtle', 'passed', '1/1', '9.5s']
    assert table[3].split() == ['temp_server', 'FAILED', '1/2', '2.0s']
    assert table[-1] == '1 of 2 exercises passed in 11.5 s'


def test_the_latest_result_of_each_exercise_is_kept_beside_the_others(tmp_path):
    path = results_file({'XDG_STATE_HOME': str(tmp_path)})
    assert path == tmp_path / 'owl-kit-lab' / 'check-results.json'
    home = results_file({'HOME': '/home/ada1'})
    assert home == Path('/home/ada1/.local/state/owl-kit-lab/check-results.json')
    failed = ExerciseResult('imu_turtle', [Criterion('moves', False)])
    record_latest(path, [failed, ExerciseResult('keyboard', [Criterion('reads keys', True)])],
                  {'imu_turtle': '4.3', 'keyboard': '3.4'}, '/ws', now=100.0)
    record_latest(path, [ExerciseResult('imu_turtle', [Criterion('moves', True)])], {'imu_turtle': '4.3'},
                  '/ws', now=200.0)
    latest = read_latest(path)
    assert latest['imu_turtle'] == {'passed': True, 'failed': 0, 'criteria': 1, 'error': '', 'section': '4.3',
                                    'at': 200.0, 'workspace': '/ws'}
    assert latest['keyboard']['passed'] is True
    assert latest['keyboard']['at'] == 100.0


@pytest.mark.parametrize('text', ['{broken', '[1, 2]', '{"exercises": 3}', ''])
def test_a_broken_results_file_reads_as_none_and_is_written_anew(tmp_path, text):
    path = tmp_path / 'check-results.json'
    path.write_text(text)
    assert read_latest(path) == {}
    record_latest(path, [ExerciseResult('keyboard', [Criterion('reads keys', True)])], {}, '/ws', now=1.0)
    assert list(read_latest(path)) == ['keyboard']


class TeacherPage(http.server.BaseHTTPRequestHandler):
    """A stand-in for the class's teacher page: keeps what it is sent, answers as told."""

    received: ClassVar[list[tuple[str, bytes]]] = []
    answer = (200, b'{"kept": []}')

    def do_POST(self):
        body = self.rfile.read(int(self.headers['Content-Length']))
        TeacherPage.received.append((self.headers['Authorization'], body))
        self.send_response(self.answer[0])
        self.send_header('Content-Type', 'application/json')
        self.end_headers()
        self.wfile.write(self.answer[1])

    def log_message(self, *args):
        pass


def test_on_a_class_server_the_latest_results_go_to_the_teachers_page_and_a_refusal_is_one_line(tmp_path):
    path = tmp_path / 'check-results.json'
    record_latest(path, [ExerciseResult('imu_turtle', [Criterion('moves', True)])], {'imu_turtle': '4.3'},
                  '/ws', now=5.0)
    assert share_latest(path, {}) is None  # no class server: nothing sent, nothing said
    server = http.server.ThreadingHTTPServer(('127.0.0.1', 0), TeacherPage)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f'http://127.0.0.1:{server.server_address[1]}/services/owl-teacher/api/results'
    environ = {'OWL_CLASS_RESULTS_URL': url, 'JUPYTERHUB_API_TOKEN': 'secret-token'}
    try:
        assert share_latest(path, environ) is None
        token, body = TeacherPage.received[-1]
        assert token == 'token secret-token'
        assert json.loads(body)['exercises']['imu_turtle']['passed'] is True
        TeacherPage.answer = (403, b'{"error": "teacher1 is not a student of this class: nothing kept"}')
        assert share_latest(path, environ) == ("the teacher's page did not take these results (403: teacher1 "
                                               'is not a student of this class: nothing kept)')
    finally:
        server.shutdown()
        server.server_close()
    gone = share_latest(path, environ)  # the page is not running
    assert gone is not None
    assert gone.startswith("the teacher's page did not take these results (")
    assert share_latest(path, {**environ, 'OWL_CLASS_RESULTS_URL': 'not a url'}) is not None
