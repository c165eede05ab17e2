import os
from collections.abc import Generator
from dataclasses import dataclass
from pathlib import Path

import pytest

# Set before any rclpy context exists in this process.
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from ros_harness import RosHarness
from x_display import VirtualDisplay, missing_tool


@pytest.fixture
def ros():
    """Processes and a probe node in a ROS domain that no other test or run shares."""
    harness = RosHarness()
    try:
        yield harness
    finally:
        harness.close()


@pytest.fixture
def xvfb():
    """A virtual X display (Xvfb) of this test's own, for tests of real windows; skipped without Xvfb."""
    tool = missing_tool()
    if tool is not None:
        pytest.skip(f'{tool} is not installed (scripts/test_prereqs.sh installs it): real windows not tested')
    display = VirtualDisplay()
    try:
        yield display
    finally:
        display.close()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A failed test also shows what each of its ROS processes printed last and whether it exited:
    a node that crashed or hung at start-up is otherwise invisible behind a graph timeout."""
    outcome = yield
    report = outcome.get_result()
    if report.when != 'call' or not report.failed:
        return
    for name, value in item.funcargs.items():
        if isinstance(value, RosHarness):
            for process in value.processes:
                state = 'running' if process.running() else f'exit code {process.popen.poll()}'
                report.sections.append((f'{name}: {process.label} ({state})', process.tail()))


# System tests run real processes over real DDS, where a rare discovery or scheduling delay can fail
# a correct test; each gets one more run (pytest-rerunfailures). Unit tests are deterministic: never.
SYSTEM_TESTS = Path(__file__).parent
SYSTEM_TEST_RERUNS = 1


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if config.getoption('usepdb'):
        return  # a failure should stop in the debugger, and the plugin refuses reruns with --pdb
    for item in items:
        if item.path.is_relative_to(SYSTEM_TESTS):
            item.add_marker(pytest.mark.flaky(reruns=SYSTEM_TEST_RERUNS))


@dataclass
class Rerun:
    first_failure: str
    outcome: str = 'passed'


# nodeid -> what a rerun test's first failure was and how its second run ended
RERUNS: dict[str, Rerun] = {}


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    if report.outcome == 'rerun':  # the call's report, then a failed teardown's: keep the first
        RERUNS.setdefault(report.nodeid, Rerun(first_line(report)))
    elif report.nodeid in RERUNS and (report.when == 'call' or not report.passed):
        RERUNS[report.nodeid].outcome = report.outcome


def first_line(report: pytest.TestReport) -> str:
    """A failure report's exception in one line, as in pytest's short test summary."""
    crash = getattr(report.longrepr, 'reprcrash', None)
    text = crash.message if crash is not None else report.longreprtext
    line = next((line.strip() for line in text.splitlines() if line.strip()), '(no message)')
    return line if len(line) <= 300 else line[:297] + '...'


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> Generator[None, None, None]:
    """A flake is never silent: after every other summary, just above the final counts line (which
    CI reads), one line per test that needed its second run."""
    result = yield
    for nodeid, rerun in RERUNS.items():
        again = ' again' if rerun.outcome == 'failed' else ''
        terminalreporter.write_line(
            f'rerun: {nodeid} {rerun.outcome}{again} on its second run; first failure: {rerun.first_failure}')
    return result


@pytest.fixture(scope='session')
def x_display():
    """One virtual X display (tests/desktop.py) for every window test of the run."""
    from desktop import VirtualDisplay
    display = VirtualDisplay()
    try:
        yield display
    finally:
        display.close()
