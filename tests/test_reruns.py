"""A failed system test gets exactly one more run, a unit test none, and every rerun is reported.

Each case runs a small pytest session in a subprocess with the project's own configuration and a
copy of tests/conftest.py, laid out like the repository (tests/ and src/<pkg>/test/).
"""

import shutil
import subprocess
import sys
from pathlib import Path

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


def run_session(root: Path, *args: str) -> subprocess.CompletedProcess:
    (root / 'tests').mkdir()
    shutil.copy(REPOSITORY / 'tests' / 'conftest.py', root / 'tests' / 'conftest.py')
    (root / 'tests' / 'test_system.py').write_text(SYSTEM_TESTS)
    (root / 'src' / 'pkg' / 'test').mkdir(parents=True)
    (root / 'src' / 'pkg' / 'test' / 'test_unit.py').write_text(UNIT_TEST)
    return subprocess.run(
        [sys.executable, '-m', 'pytest', '-c', str(REPOSITORY / 'pyproject.toml'), '--rootdir', str(root),
         '--confcutdir', str(root), *args],
        cwd=root, capture_output=True, text=True, timeout=120)


def test_a_system_test_that_fails_once_passes_and_its_first_failure_is_reported_last(tmp_path):
    session = run_session(tmp_path, 'tests/test_system.py::test_flaky')
    lines = session.stdout.splitlines()
    assert session.returncode == 0, session.stdout
    assert lines[-2] == ('rerun: tests/test_system.py::test_flaky passed on its second run; '
                         'first failure: AssertionError: a discovery delay'), session.stdout
    assert lines[-1].startswith('1 passed, 1 rerun in'), session.stdout


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
