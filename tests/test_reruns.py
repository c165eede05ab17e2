"""How make test runs tests: a failed system test gets exactly one more run, a unit test none.

Every rerun is reported; suites on one machine share its system-test slots.

Each case runs small pytest sessions in subprocesses with the project's own configuration and a
copy of tests/conftest.py, laid out like the repository (tests/ and src/<pkg>/test/), with a slot
folder of their own (the suite running them holds the machine's slots).
"""

import json
import os
import re
import shutil
import subprocess
import sys
from itertools import permutations
from pathlib import Path

import pytest
import spare_cpu

SLOTS = (os.cpu_count() or 1) + 1  # as conftest's SYSTEM_TEST_SLOTS
REPOSITORY = Path(__file__).resolve().parent.parent

# A test that fails on its first run only remembers that run in a file next to it.
SYSTEM_TESTS = '''
from pathlib import Path


def ran_before(name):
    marker = Path(__file__).with_name(name)
    before = marker.exists()
    marker.touch()
    return before


def test_flaky():
    assert ran_before('flaky.ran'), 'a discovery delay\\nthat spans lines'


def test_broken():
    assert 1 == 2, 'broken for good'


def test_fine():
    pass
'''

UNIT_TEST = '''
from pathlib import Path


def test_flaky_unit():
    marker = Path(__file__).with_name('unit.ran')
    before = marker.exists()
    marker.touch()
    assert before, 'a unit test failing once'
'''


def lay_out(root: Path, system_tests: str) -> None:
    (root / 'tests').mkdir(parents=True)
    shutil.copy(REPOSITORY / 'tests' / 'conftest.py', root / 'tests' / 'conftest.py')
    (root / 'tests' / 'test_system.py').write_text(system_tests)
    (root / 'src' / 'pkg' / 'test').mkdir(parents=True)
    (root / 'src' / 'pkg' / 'test' / 'test_unit.py').write_text(UNIT_TEST)


def start_session(root: Path, slots: Path, *args: str, spare_idle: float | None = None,
                  spares: int = 1) -> subprocess.Popen:
    """A pytest session of root's tests in slots; with no spare slot unless spare_idle is given."""
    spare = {'OWL_TEST_SPARE_SLOTS': '0'} if spare_idle is None else {'OWL_TEST_SPARE_SLOTS': str(spares),
                                                                      'OWL_TEST_SPARE_IDLE': str(spare_idle)}
    return subprocess.Popen(
        [sys.executable, '-m', 'pytest', '-c', str(REPOSITORY / 'pyproject.toml'), '--rootdir', str(root),
         '--confcutdir', str(root), *args],
        cwd=root, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        env={**os.environ, 'OWL_TEST_SLOT_DIR': str(slots), **spare})


def run_session(root: Path, *args: str) -> subprocess.CompletedProcess:
    lay_out(root, SYSTEM_TESTS)
    process = start_session(root, root / 'slots', *args)
    stdout, _ = process.communicate(timeout=120)
    return subprocess.CompletedProcess(process.args, process.returncode, stdout)


def test_a_system_test_that_fails_once_passes_and_its_first_failure_is_reported_last(tmp_path):
    session = run_session(tmp_path, 'tests/test_system.py::test_flaky')
    lines = session.stdout.splitlines()
    assert session.returncode == 0, session.stdout
    assert lines[-2] == ('rerun: tests/test_system.py::test_flaky passed on its second run; '
                         'first failure: AssertionError: a discovery delay'), session.stdout
    assert lines[-1].startswith('1 passed, 1 rerun in'), session.stdout
    assert lines[-3] == 'first failures of rerun tests, in full: log/reruns/', session.stdout
    report = (tmp_path / 'log' / 'reruns' / 'tests_test_system.py_test_flaky.txt').read_text()
    assert 'a discovery delay\nE         that spans lines' in report, report


def test_a_system_test_failing_twice_fails_and_a_unit_test_is_never_rerun(tmp_path):
    session = run_session(tmp_path, 'tests', 'src')
    lines = session.stdout.splitlines()
    assert session.returncode == 1, session.stdout
    assert lines[-3:-1] == [
        'rerun: tests/test_system.py::test_flaky passed on its second run; '
        'first failure: AssertionError: a discovery delay',
        'rerun: tests/test_system.py::test_broken failed again on its second run; '
        'first failure: AssertionError: broken for good',
    ], session.stdout
    assert lines[-1].startswith('2 failed, 2 passed, 2 rerun in'), session.stdout
    assert 'FAILED src/pkg/test/test_unit.py::test_flaky_unit' in session.stdout
    assert not [line for line in lines if line.startswith('rerun: src/')], session.stdout


def test_reruns_in_parallel_workers_are_reported_by_the_controller(tmp_path):
    """`make test` runs the suite in pytest-xdist workers: the reruns happen there, the report at the end."""
    session = run_session(tmp_path, '-n', '2', 'tests', 'src')
    lines = session.stdout.splitlines()
    assert session.returncode == 1, session.stdout
    assert sorted(lines[-3:-1]) == [
        'rerun: tests/test_system.py::test_broken failed again on its second run; '
        'first failure: AssertionError: broken for good',
        'rerun: tests/test_system.py::test_flaky passed on its second run; '
        'first failure: AssertionError: a discovery delay',
    ], session.stdout
    assert lines[-1].startswith('2 failed, 2 passed, 2 rerun in'), session.stdout
    assert not [line for line in lines if line.startswith('rerun: src/')], session.stdout
    reports = sorted(path.name for path in (tmp_path / 'log' / 'reruns').iterdir())
    assert reports == ['tests_test_system.py_test_broken.txt', 'tests_test_system.py_test_flaky.txt']


PROCESS_OUTPUT_FAILURE = '''
def test_node_output():
    output = '[INFO] [launch]: All log files can be found below /root/.ros/log/x\\n' \\
        '[node-1] Traceback (most recent call last):\\n' \\
        '[node-1] RuntimeError: the real reason\\n' \\
        '[INFO] [node-1]: process has died'
    assert 'Traceback' not in output, output
'''


def test_a_failure_showing_a_process_output_is_reported_by_the_exception_it_names(tmp_path):
    lay_out(tmp_path, PROCESS_OUTPUT_FAILURE)
    process = start_session(tmp_path, tmp_path / 'slots', 'tests')
    stdout, _ = process.communicate(timeout=120)
    assert ('rerun: tests/test_system.py::test_node_output failed again on its second run; '
            'first failure: AssertionError: ... [node-1] RuntimeError: the real reason') in stdout, stdout


# How long each timed test below runs: far longer than a test waits for a free slot (0.1 s polls)
# and than what pytest does between two tests, so tests that may run side by side do overlap.
RUN_FOR = 1.0

# Start of a test module whose tests, once every worker of the run (of both sessions: they share a
# slot folder) has collected it, spend RUN_FOR s and append when they ran to the session's ran.jsonl.
# Workers start seconds apart on two cores: a clock started only when all are up means that
# nothing but the slots keeps the tests from all running at once.
TIMED_MODULE = '''
import json
import os
import time
from pathlib import Path

import pytest

WORKERS = Path(os.environ['OWL_TEST_SLOT_DIR']).parent / 'workers'
if 'PYTEST_XDIST_WORKER' in os.environ:
    WORKERS.mkdir(exist_ok=True)
    (WORKERS / str(os.getpid())).touch()


def run_for_a_while(*name):
    deadline = time.monotonic() + 60
    while len(list(WORKERS.iterdir())) < WORKER_COUNT and time.monotonic() < deadline:
        time.sleep(0.02)
    started = time.time()
    time.sleep(RUN_FOR)
    with open(Path(__file__).parents[1] / 'ran.jsonl', 'a') as ran:
        ran.write(json.dumps([*name, started, time.time()]) + '\\n')
'''


def timed_module(workers: int, tests: str, run_for: float = RUN_FOR) -> str:
    """TIMED_MODULE for a run of that many workers in all, each test run_for s long, then the tests."""
    return TIMED_MODULE + f'\nWORKER_COUNT = {workers}\nRUN_FOR = {run_for}\n\n' + tests


def most_at_once(runs: list[list[float]]) -> int:
    """The most of runs ([start, end] each) under way at one moment."""
    return max(sum(start <= moment < end for start, end in runs) for moment, _ in runs)


def test_suites_side_by_side_run_no_more_system_tests_at_once_than_the_machine_has_slots(tmp_path):
    sessions = []
    for suite in range(2):  # two suites of SLOTS workers, each test RUN_FOR s long
        root = tmp_path / f'suite{suite}'
        tests = ''.join(f'\ndef test_{n}():\n    run_for_a_while()\n' for n in range(SLOTS))
        lay_out(root, timed_module(2 * SLOTS, tests))
        sessions.append(start_session(root, tmp_path / 'slots', '-n', str(SLOTS), 'tests'))
    for process in sessions:
        stdout, _ = process.communicate(timeout=120)
        assert process.returncode == 0, stdout
    runs = [json.loads(line) for suite in range(2)
            for line in (tmp_path / f'suite{suite}' / 'ran.jsonl').read_text().splitlines()]
    assert len(runs) == 2 * SLOTS
    assert most_at_once(runs) <= SLOTS, runs  # without slots, up to twice as many


def test_spare_slots_let_more_tests_run_while_the_machine_idles_lent_half_a_second_apart(tmp_path):
    """With any idle share enough (0), both spare slots are taken: SLOTS + 2 tests at once, no more.

    The tests outlast spare_cpu.WINDOW, which a worker watches the machine before its first spare
    slot. The second spare comes SPARE_SPACING (0.5 s) after the first, not a WINDOW of its own later.
    """
    workers = SLOTS + 3
    tests = ''.join(f'\ndef test_{n}():\n    run_for_a_while()\n' for n in range(workers))
    lay_out(tmp_path, timed_module(workers, tests, run_for=spare_cpu.WINDOW + 2))
    session = start_session(tmp_path, tmp_path / 'slots', '-n', str(workers), 'tests', spare_idle=0.0,
                            spares=2)
    stdout, _ = session.communicate(timeout=120)
    assert session.returncode == 0, stdout
    runs = [json.loads(line) for line in (tmp_path / 'ran.jsonl').read_text().splitlines()]
    assert most_at_once(runs) == SLOTS + 2, runs
    first_spare, second_spare = sorted(start for start, _ in runs)[SLOTS:SLOTS + 2]
    # when each test began, a little after it took its slot: 0.1 s of slack
    assert 0.4 <= second_spare - first_spare < spare_cpu.WINDOW, runs


def test_a_test_that_starts_no_process_runs_while_every_slot_is_taken(tmp_path):
    """SLOTS tests fill the slots (no spare one); a test marked no_processes runs beside them all."""
    tests = ''.join(f'\ndef test_{n}():\n    run_for_a_while()\n' for n in range(SLOTS))
    tests += "\n@pytest.mark.no_processes\ndef test_reads_files():\n    run_for_a_while()\n"
    lay_out(tmp_path, timed_module(SLOTS + 1, tests))
    session = start_session(tmp_path, tmp_path / 'slots', '-n', str(SLOTS + 1), 'tests')
    stdout, _ = session.communicate(timeout=120)
    assert session.returncode == 0, stdout
    runs = [json.loads(line) for line in (tmp_path / 'ran.jsonl').read_text().splitlines()]
    assert most_at_once(runs) == SLOTS + 1, runs


PROC_STAT = 'cpu  {user} 0 {system} {idle} {iowait} 0 0 0 0 0\ncpu0 1 2 3 4 5 6 7 8 9 10\nintr 1\n'


def proc_stat(user: int, system: int, idle: int, iowait: int = 0) -> str:
    return PROC_STAT.format(user=user, system=system, idle=idle, iowait=iowait)


def test_cpu_times_are_the_idle_and_all_ticks_of_proc_stats_first_line():
    assert spare_cpu.cpu_times(proc_stat(user=100, system=50, idle=800, iowait=20)) == (820, 970)
    with pytest.raises(ValueError, match="not /proc/stat: its first line is 'intr 1'"):
        spare_cpu.cpu_times('intr 1\n')


def test_the_idle_share_is_over_the_last_window_and_unknown_before_a_window_has_passed():
    now = [0.0]
    stats = iter([proc_stat(0, 0, 0), proc_stat(50, 0, 50), proc_stat(100, 0, 100),
                  proc_stat(200, 0, 100), proc_stat(200, 0, 300)])
    watch = spare_cpu.IdleWatch(read=lambda: next(stats), clock=lambda: now[0])
    assert watch.idle_share() is None  # the first sample
    now[0] = spare_cpu.WINDOW / 2
    assert watch.idle_share() is None  # none a window old yet
    now[0] = spare_cpu.WINDOW
    assert watch.idle_share() == 0.5  # since t=0: 100 of 200 ticks idle
    now[0] = spare_cpu.WINDOW * 1.5
    assert watch.idle_share() == 0.25  # since t=WINDOW/2, the newest sample a window old: 50 of 200
    now[0] = spare_cpu.WINDOW * 2.5
    assert watch.idle_share() == 1.0  # since t=1.5 WINDOW: 200 of 200, the machine idle lately


# Two tests marked whole_kit and four unmarked; each appends its name and when it ran.
MARKED_TESTS = '''
@pytest.mark.whole_kit
@pytest.mark.parametrize('n', range(2))
def test_whole_kit(n):
    run_for_a_while(f'whole_kit {n}')


@pytest.mark.parametrize('n', range(4))
def test_unmarked(n):
    run_for_a_while(f'unmarked {n}')
'''


def test_marked_tests_hold_their_share_of_the_slots_and_tests_that_fit_run_side_by_side(tmp_path):
    """whole_kit holds two of the CPUs + 1 slots, the rest one each; tests that fit in the free slots meet.

    In 4 workers: an unmarked test runs beside another, and (with more than two slots) a whole_kit test
    beside an unmarked one.
    """
    lay_out(tmp_path, timed_module(4, MARKED_TESTS))
    session = start_session(tmp_path, tmp_path / 'slots', '-n', '4', 'tests')
    stdout, _ = session.communicate(timeout=120)
    assert session.returncode == 0, stdout
    runs = {name: (start, end) for name, start, end in
            (json.loads(line) for line in (tmp_path / 'ran.jsonl').read_text().splitlines())}
    assert len(runs) == 6, runs
    share = {'whole_kit': min(2, SLOTS), 'unmarked': 1}
    for name, (start, _) in runs.items():
        running = [other for other, (begun, ended) in runs.items() if begun <= start < ended]
        assert sum(share[other.split()[0]] for other in running) <= SLOTS, (name, running, runs)

    def met(kind: str, others: tuple[str, ...]) -> bool:
        return any(a[0] < b[1] and b[0] < a[1] for (name, a), (other, b) in permutations(runs.items(), 2)
                   if name.startswith(kind) and other.startswith(others))

    assert met('unmarked', ('unmarked', 'whole_kit')), runs  # one slot each: not one at a time
    if SLOTS > 2:  # a whole_kit test holds two slots, not all
        assert met('whole_kit', ('unmarked',)), runs


HANGING_TEST = '''
import time

import greenlet


def test_hangs_in_a_worker():
    def event_loop():
        time.sleep(60)

    greenlet.greenlet(event_loop).switch()  # as in Playwright's sync API: the test waits, a loop runs
'''


def test_a_test_at_its_timeout_in_a_worker_leaves_every_stack_in_the_output(tmp_path):
    lay_out(tmp_path, HANGING_TEST)
    session = start_session(tmp_path, tmp_path / 'slots', '-n', '1', '-o', 'timeout=3',
                            '-p', 'no:rerunfailures', 'tests')
    stdout, _ = session.communicate(timeout=120)
    assert session.returncode == 1, stdout
    assert "crashed while running 'tests/test_system.py::test_hangs_in_a_worker'" in stdout, stdout
    assert re.search(r'File ".*test_system\.py", line 9 in event_loop', stdout), stdout
    greenlet_stack = r'Greenlet \(most recent call last\):\n(.*\n)*.*line 11, in test_hangs_in_a_worker'
    assert re.search(greenlet_stack, stdout), stdout
