"""`make test`'s closing report: the 25 slowest tests and the time each group of tests took.

A pytest plugin (pyproject.toml's addopts load it with -p, for the whole suite, src/'s unit tests
too). Each test's time is its set-up, call and tear-down together; a group's is the sum of its tests'
(with several workers the groups overlap in time, so the sum of the groups is more than the run's
wall time, which is printed beside them).

Groups: style (ruff, mypy, the layout), browser (a test with a Chromium page), system (tests/),
unit (src/<group>/<package>/test/). Every test's time, slowest first, is also written to
log/test-durations.txt (one line a test: seconds, group, CPU seconds, when it started and ended in
seconds from the first test's start, the seconds it waited for its slots before its set-up, its
worker, node id), for finding where the time goes: which tests run at the end, alone, which keep the
machine busy, and where workers wait for slots.

A test's CPU is its worker's own and that of the processes the worker waited for, from the test's
set-up to the end of its tear-down: what its processes used, as the harness stops and waits for every
process it starts (a module's Chromium counts in the module's last test; a daemon that detaches from
its parent is not counted).
"""

from __future__ import annotations

import os
import resource
import time
from collections import defaultdict
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
DURATIONS_FILE = TESTS.parent / 'log' / 'test-durations.txt'
STYLE_MODULES = {'test_code_style.py', 'test_layout.py'}
SLOWEST = 25
GROUPS = ('system', 'browser', 'unit', 'style')

durations: dict[str, float] = defaultdict(float)
groups: dict[str, str] = {}
spans: dict[str, tuple[float, float]] = {}  # node id -> (first phase's start, last phase's end), epoch s
cpu_used: dict[str, float] = defaultdict(float)  # node id -> CPU seconds, its reruns' too
cpu_at_setup: dict[str, float] = {}  # in a worker: node id -> cpu_seconds() as its set-up began
waited: dict[str, float] = defaultdict(float)  # node id -> s waited for slots (WAITED) before it ran
workers: dict[str, str] = {}  # node id -> the pytest-xdist worker that ran it
WAITED = 'waited'  # the user property conftest sets: s a test waited for its slots before its set-up
started = time.monotonic()


def group_of(item: pytest.Item) -> str:
    """Which group a test belongs to (see the module's docstring)."""
    if item.path.name in STYLE_MODULES:
        return 'style'
    if not item.path.is_relative_to(TESTS):
        return 'unit'
    fixtures = getattr(item, 'fixturenames', ())
    return 'browser' if 'page' in fixtures or 'browser' in fixtures else 'system'


def cpu_seconds() -> float:
    """User and system CPU of this process and of the children it has waited for, in seconds."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item: pytest.Item) -> None:
    # user_properties travel with the reports from a pytest-xdist worker to the controller
    item.user_properties.append(('group', group_of(item)))
    item.user_properties.append(('worker', os.environ.get('PYTEST_XDIST_WORKER', '-')))
    cpu_at_setup[item.nodeid] = cpu_seconds()


@pytest.hookimpl(wrapper=True)
def pytest_runtest_teardown(item: pytest.Item) -> object:
    try:
        return (yield)
    finally:  # before the tear-down's report is made, which carries the property
        started_at = cpu_at_setup.pop(item.nodeid, None)
        if started_at is not None:
            item.user_properties.append(('cpu', cpu_seconds() - started_at))


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    durations[report.nodeid] += report.duration
    if report.when == 'teardown':
        cpu = [value for name, value in report.user_properties if name == 'cpu']
        if cpu and isinstance(cpu[-1], float):  # the last: a rerun's item keeps its first run's too
            cpu_used[report.nodeid] += cpu[-1]
    first, last = spans.get(report.nodeid, (report.start, report.stop))
    spans[report.nodeid] = (min(first, report.start), max(last, report.stop))
    properties = dict(report.user_properties)
    if isinstance(group := properties.get('group'), str):
        groups[report.nodeid] = group
    if isinstance(worker := properties.get('worker'), str):
        workers[report.nodeid] = worker
    if report.when == 'setup' and isinstance(wait := properties.get(WAITED), float):
        waited[report.nodeid] = wait  # a rerun runs within the same wait


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if not durations or hasattr(terminalreporter.config, 'workerinput'):
        return
    write = terminalreporter.write_line
    slowest = sorted(durations.items(), key=lambda item: -item[1])
    DURATIONS_FILE.parent.mkdir(parents=True, exist_ok=True)
    origin = min(start for start, _ in spans.values()) if spans else 0.0

    def group_name(nodeid: str) -> str:
        return groups.get(nodeid, 'unit')

    def span(nodeid: str) -> str:  # its start and end, from the first test's start
        start, stop = spans.get(nodeid, (origin, origin))
        return f'{start - origin:7.1f} {stop - origin:7.1f}'

    DURATIONS_FILE.write_text(''.join(
        f'{seconds:8.2f} {group_name(nodeid):8} {cpu_used[nodeid]:8.2f} {span(nodeid)} '
        f'{waited[nodeid]:6.1f} {workers.get(nodeid, "-"):5} {nodeid}\n'
        for nodeid, seconds in slowest))
    write(f'slowest {SLOWEST} tests (set-up, call and tear-down; all of them: '
          f'{DURATIONS_FILE.relative_to(TESTS.parent)}):')
    for nodeid, seconds in slowest[:SLOWEST]:
        write(f'  {seconds:7.1f} s  {nodeid}')
    totals = dict.fromkeys(GROUPS, 0.0)
    cpu_totals = dict.fromkeys(GROUPS, 0.0)
    counts = dict.fromkeys(GROUPS, 0)
    for nodeid, seconds in durations.items():
        group = groups.get(nodeid, 'unit')
        totals[group] += seconds
        cpu_totals[group] += cpu_used[nodeid]
        counts[group] += 1
    parts = ', '.join(f'{group} {totals[group]:.0f} s ({counts[group]} tests)' for group in GROUPS)
    write(f'time per group, summed over tests: {parts}; the run took {time.monotonic() - started:.0f} s')
    parts = ', '.join(f'{group} {cpu_totals[group]:.0f} s' for group in GROUPS)
    write(f'CPU per group (its tests and their processes): {parts}')
