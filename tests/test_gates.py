"""Nothing passes untested in CI: a missing browser, Xvfb or namespace fails there instead of skipping."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from gates import ALLOWED_IN_CI

ROOT = Path(__file__).resolve().parents[1]
PREREQS = ROOT / 'scripts' / 'test_prereqs.sh'
NEEDS_A_BROWSER = """
from gates import prerequisite_missing

def test_needs_a_browser():
    prerequisite_missing('chromium not found')
"""


def without_ci(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != 'CI'}
    env.update(extra)
    return env


def run_in_a_suite(tmp_path: Path, test_source: str, ci: bool, gate: bool = True) -> str:
    """The output of pytest with our settings (pyproject.toml) over one test file in tmp_path.

    gate: with gates.py as a plugin, as tests/conftest.py registers it; without, only what the test
    calls of it acts.
    """
    (tmp_path / 'test_one.py').write_text('import pytest\n\n' + test_source)
    env = without_ci(**({'CI': 'true'} if ci else {}))
    result = subprocess.run([sys.executable, '-m', 'pytest', '-c', str(ROOT / 'pyproject.toml'),
                             *(['-p', 'gates'] if gate else []), '-p', 'no:xdist', '-p', 'no:randomly',
                             '-p', 'no:rerunfailures', str(tmp_path / 'test_one.py')],
                            cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    return result.stdout + result.stderr


@pytest.mark.parametrize(('ci', 'outcome'), [(False, '1 skipped'), (True, '1 failed')])
def test_a_missing_prerequisite_skips_here_and_fails_in_ci(tmp_path: Path, ci: bool, outcome: str):
    output = run_in_a_suite(tmp_path, NEEDS_A_BROWSER, ci, gate=False)
    assert outcome in output, output


UNGATED_SKIP = """
def test_needs_a_frobnicator():
    pytest.skip('no frobnicator here')
"""
UNGATED_SKIPIF = """
@pytest.mark.skipif(True, reason='no frobnicator here')
def test_needs_a_frobnicator():
    pass
"""
ALLOWED_SKIP = """
def test_needs_multicast():
    pytest.skip('no multicast-capable interface here: [Errno 19] No such device')
"""
EXPECTED_FAILURE = """
@pytest.mark.xfail(reason='a known defect', strict=True)
def test_a_known_defect():
    assert False
"""


@pytest.mark.parametrize(('source', 'ci', 'outcome', 'says'), [
    (UNGATED_SKIP, False, '1 skipped', 'no frobnicator here'),  # -rfEs: the reason in the summary
    (UNGATED_SKIP, True, '1 failed', 'skipped in CI: no frobnicator here'),
    (UNGATED_SKIPIF, True, '1 error', 'skipped in CI: no frobnicator here'),  # in set-up: an error
    (ALLOWED_SKIP, True, '1 skipped', 'no multicast-capable interface here'),
    (EXPECTED_FAILURE, True, '1 xfailed', ''),
], ids=['skip-here', 'skip-in-ci', 'skipif-in-ci', 'allowed-in-ci', 'xfail-in-ci'])
def test_in_ci_a_skip_off_the_allow_list_fails_and_its_reason_is_printed(
        tmp_path: Path, source: str, ci: bool, outcome: str, says: str):
    output = run_in_a_suite(tmp_path, source, ci)
    assert outcome in output, output
    assert says in output, output


def test_every_reason_allowed_in_ci_says_why():
    assert 0 < len(ALLOWED_IN_CI) <= 5
    assert all(len(why) > 40 for why in ALLOWED_IN_CI.values()), ALLOWED_IN_CI


def machine_without_the_programs(tmp_path: Path) -> Path:
    """A PATH with only what the script needs to run and none of the programs it looks for.

    Its apt-get fails, as on a machine whose package mirror is unreachable.
    """
    path = tmp_path / 'bin'
    path.mkdir()
    for tool in ('bash', 'id', 'mkdir', 'dirname'):
        found = shutil.which(tool)
        assert found is not None
        (path / tool).symlink_to(found)
    apt_get = path / 'apt-get'
    apt_get.write_text('#!/bin/sh\necho "E: mirror unreachable" >&2\nexit 100\n')
    apt_get.chmod(0o755)
    return path


@pytest.mark.parametrize(('ci', 'code', 'says'), [(False, 0, 'skip'), (True, 1, 'the run fails')])
def test_the_prerequisite_script_fails_a_ci_run_when_chromium_is_absent(tmp_path: Path, ci: bool, code: int,
                                                                         says: str):
    path = machine_without_the_programs(tmp_path)
    env = without_ci(PATH=str(path), **({'CI': 'true'} if ci else {}))
    result = subprocess.run([str(path / 'bash'), str(PREREQS)], env=env, capture_output=True, text=True,
                            timeout=60)
    output = result.stdout + result.stderr
    assert result.returncode == code, output
    assert 'chromium' in output, output
    assert says in output, output
