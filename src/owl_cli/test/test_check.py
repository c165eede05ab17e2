"""owl check's logic without ROS: catalogue, workspace and build decision, judgements, report."""

import json
import os
import time

import pytest
from owl_cli import check_catalogue as catalogue
from owl_cli import check_criteria as judge
from owl_cli import check_workspace as ws
from owl_cli.check_report import Criterion, ExerciseResult, exit_code, summary_table, to_json
from owl_cli.main import main

# -- catalogue -------------------------------------------------------------------------------------


def test_every_exercise_has_a_check_and_a_unique_id():
    from owl_cli.check_ros import CHECKS

    assert [e.id for e in catalogue.EXERCISES] == list(catalogue.BY_ID)
    assert set(catalogue.BY_ID) == set(CHECKS)


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
        assert line.endswith(exercise.description)


# -- command line (no ROS: the bad inputs stop before any check runs) -------------------------------


def test_list_and_bad_input_exit_codes(capsys, tmp_path, monkeypatch):
    assert main(['check', '--list']) == 0
    assert 'imu_turtle' in capsys.readouterr().out
    assert main(['check', 'imu_turtel']) == 2
    assert "did you mean 'imu_turtle'" in capsys.readouterr().err
    assert main(['check']) == 2
    assert 'give exercise ids or --all' in capsys.readouterr().err
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


# -- judgements ------------------------------------------------------------------------------------


def test_fahrenheit_names_the_listing_typo():
    assert judge.fahrenheit(100.0, 212.0).passed
    typo = judge.fahrenheit(100.0, 482.0)
    assert not typo.passed and "listing's temp_c * 9 / 2" in typo.hint
    other = judge.fahrenheit(100.0, 300.0)
    assert not other.passed and 'formula 1' in other.hint
    assert judge.kelvin(0.0, 273.15).passed and not judge.kelvin(0.0, 273.0).passed


def test_the_turtle_judgement_tells_a_swap_from_a_sign_from_nothing():
    assert judge.turtle_response('pitch', 0.6, 0.0).passed
    assert judge.turtle_response('yaw', 0.0, 0.75).passed
    assert 'check the sign of pitch' in judge.turtle_response('pitch', -0.6, 0.0).hint
    assert 'check the sign of yaw' in judge.turtle_response('yaw', 0.0, -0.75).hint
    assert 'swapped' in judge.turtle_response('pitch', 0.0, 0.4).hint
    assert 'swapped' in judge.turtle_response('yaw', 0.5, 0.0).hint
    still = judge.turtle_response('pitch', 0.0, 0.0)
    assert not still.passed and 'does not move when the IMU pitches forward' in still.hint
    assert judge.standing_still(0.01, -0.01).passed and not judge.standing_still(0.3, 0.0).passed


def test_bounds_rate_and_sine():
    assert judge.bounded_goal('pan', [0.0, 1.0, 1.5708], -1.5708, 1.5708, 'Left is held').passed
    unbounded = judge.bounded_goal('pan', [0.0, 2.0, 4.8], -1.5708, 1.5708, 'Left is held')
    assert not unbounded.passed and '+4.80' in unbounded.hint
    assert not judge.bounded_goal('pan', [], -1, 1, 'Left is held').passed
    assert judge.rate([0.0, 0.5, 1.0]) == 2.0 and judge.rate([1.0]) == 0.0
    assert judge.oscillates([0.0, 0.3, 0.6, 0.5])
    assert not judge.oscillates([0.0, 0.3, 0.6, 0.9])  # a ramp
    assert not judge.oscillates([0.0, 0.05, 0.0])  # too small
    assert judge.in_range('numbers', [1, 2, 3], 1, 3, 'x').passed
    assert not judge.in_range('numbers', [1, 50], 1, 3, 'x').passed


# -- report ----------------------------------------------------------------------------------------


def test_exit_codes_json_and_the_summary_table():
    good = ExerciseResult('imu_turtle', [Criterion('a', True)], 9.5)
    bad = ExerciseResult('temp_server', [Criterion('a', True), Criterion('b', False, 'hint')], 2.0)
    assert exit_code([good]) == 0 and exit_code([good, bad]) == 1
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
