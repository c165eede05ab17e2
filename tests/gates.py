"""Nothing passes untested in CI: a test that cannot run here skips, and in CI (`CI=true`) fails.

On a developer's machine a missing Chromium or Xvfb is one skip line with the install command (the
run prints every skip's reason, `-rfEs`). In CI the same test fails, so a green run means it ran.
prerequisite_missing says so in the test itself; as a plugin (tests/conftest.py registers it for
every test of the run, src/'s too) this module also fails any other skip in CI whose reason is not on
ALLOWED_IN_CI, whoever wrote it: pytest.skip, skipif, importorskip.
"""

import os
from collections.abc import Generator
from typing import NoReturn

import pytest

# Skips that CI may keep, each reason (its start) with why: what they leave out is the machine's,
# and another test covers the code. Keep this short: every entry is a test that proves nothing.
ALLOWED_IN_CI = {
    'this machine lacks libGL or glib': 'the GUI build of OpenCV cannot load there; the fallback that '
                                        'replaces it is what such a machine runs, and its tests run',
    'no multicast-capable interface here': "the machine's network, not ros2 doctor: without multicast the "
                                           'hello check cannot listen; its unicast and parsing tests run',
}


IN_CI_IT_FAILS = 'in CI (CI=true) a test that cannot run fails'


def in_ci() -> bool:
    return os.environ.get('CI') == 'true'


def prerequisite_missing(reason: str) -> NoReturn:
    """Skip the test for reason, or fail it in CI."""
    if in_ci():
        pytest.fail(f'{reason}; {IN_CI_IT_FAILS}', pytrace=False)
    pytest.skip(reason)


def skip_reason(report: pytest.TestReport) -> str:
    """The reason a skipped test's report gives (pytest keeps it as (file, line, 'Skipped: reason'))."""
    longrepr = report.longrepr
    text = longrepr[2] if isinstance(longrepr, tuple) else str(longrepr)
    return text.removeprefix('Skipped: ')


def allowed_in_ci(reason: str) -> bool:
    return reason.startswith(tuple(ALLOWED_IN_CI))


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo) -> Generator[None, pytest.TestReport,
                                                                                        pytest.TestReport]:
    """In CI, a skip whose reason is not on ALLOWED_IN_CI becomes a failure saying so."""
    report = yield
    if in_ci() and report.skipped and not hasattr(report, 'wasxfail'):
        reason = skip_reason(report)
        if not allowed_in_ci(reason):
            report.outcome = 'failed'
            report.longrepr = (f'skipped in CI: {reason}; {IN_CI_IT_FAILS} '
                               '(unless its reason is on tests/gates.py ALLOWED_IN_CI, with why)')
    return report
