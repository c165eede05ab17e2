import atexit
import faulthandler
import gc
import os
import re
import shutil
import sys
import tempfile
import threading
import time
import traceback
from collections.abc import Generator
from contextlib import ExitStack
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import pytest

# Set before any rclpy context exists in this process.
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'
# No page a test starts joins the user's own front door (owl_web.pages): a test that wants one sets
# its own folder and port (RosSandbox gives each sandbox a folder of its own besides).
os.environ['OWL_PAGES_DIR'] = tempfile.mkdtemp(prefix='owl-test-pages-')
os.environ['OWL_FRONT_DOOR'] = 'off'

import gates
import suite_report
from gates import prerequisite_missing
from owl_common.processes import LEASE_DIR, try_lock_file
from ros_harness import RosHarness
from spare_cpu import IdleSampler
from web_harness import Browser, BrowserPage, chromium_missing

atexit.register(shutil.rmtree, os.environ['OWL_PAGES_DIR'], True)


@pytest.fixture
def ros():
    """Processes and a probe node in a ROS domain that no other test or run shares."""
    harness = RosHarness()
    try:
        yield harness
    finally:
        harness.close()


@pytest.fixture(scope='module')
def browser():
    """Headless Chromium (Debian's, through Playwright), started once per test module.

    While it runs, Playwright's event loop is the main thread's, where no other test could run one
    (asyncio.run).
    """
    missing = chromium_missing()
    if missing:
        prerequisite_missing(missing)
    started = Browser()
    try:
        yield started
    finally:
        started.close()


@pytest.fixture
def page(browser):
    """A fresh browser page; any console error or uncaught exception on it fails the test."""
    opened = browser.new_page()
    try:
        yield opened
    finally:
        opened.close()


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item: pytest.Item):
    """A test that passed fails if its page logged a console error or threw.

    A page that works only on the surface is not working.
    """
    result = yield
    page = item.funcargs.get('page') if hasattr(item, 'funcargs') else None
    if isinstance(page, BrowserPage) and page.console_errors:
        raise AssertionError(f'{len(page.console_errors)} console error(s) on the page; the first: '
                             f'{page.console_errors[0]}')
    return result


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """A failed test also shows what each of its ROS processes printed last and whether it exited.

    A node that crashed or hung at start-up is otherwise invisible behind a graph timeout.
    """
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


# The class server's tests and bench need the students' lab, a build of this checkout (a minute or
# two of both cores): one worker builds it as the run begins, holding two slots as a whole_kit test
# does, and a test marked class_lab waits for it before it takes its slots (make test runs a worker
# more than there are slots). At the lowest priority instead, on a slow machine the build got no CPU
# until the other tests were nearly done (900 s into a 1400 s run), and the class tests ran last, alone.
CLASS_LAB = 'class_lab'


def needs_class_lab(item: pytest.Item) -> bool:
    # Only root makes the class's accounts: elsewhere these tests stop at their prerequisite.
    return item.get_closest_marker(CLASS_LAB) is not None and os.geteuid() == 0


# These modules' tests run first, in this order, the longest of each module (marked with the longest
# timeouts) at its head. pytest-xdist's worksteal gives each worker a run of the suite's order and
# lets an idle one take the back half of another's: the head of the order runs on one worker, first.
# The class server's tests share a hub of three students (module-scoped): when a worker's back half
# split them, two to four workers started hubs of their own (the run 40 s longer, its CPU 15 % more).
# Owl check's runs over the reference solutions (10-33 s each) had started late and run alone at the
# suite's end (17 s of a 660 s run).
FIRST_MODULES = ('test_class_server.py', 'test_owl_check.py')


def run_order(item: pytest.Item) -> tuple[int, float]:
    """The sort key of the run's order: FIRST_MODULES' tests first, longest timeout first in each."""
    if item.path.name not in FIRST_MODULES or not item.path.is_relative_to(SYSTEM_TESTS):
        return len(FIRST_MODULES), 0.0
    timeout = item.get_closest_marker('timeout')
    return FIRST_MODULES.index(item.path.name), -float(timeout.args[0]) if timeout and timeout.args else 0.0


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    items.sort(key=run_order)  # stable: the rest keep pytest's order
    if config.getoption('collectonly'):
        return  # nothing runs (make test's first collections write the rewritten test modules)
    if os.environ.get('PYTEST_XDIST_WORKER', 'gw0') == 'gw0' and any(map(needs_class_lab, items)):
        threading.Thread(target=build_lab_in_slots, name='class lab build', daemon=True).start()
    if config.getoption('usepdb'):
        return  # a failure should stop in the debugger, and the plugin refuses reruns with --pdb
    for item in items:
        if item.path.is_relative_to(SYSTEM_TESTS):
            item.add_marker(pytest.mark.flaky(reruns=SYSTEM_TEST_RERUNS))


# Machine-wide, at most this many system tests run at once, whichever suite they belong to: one
# suite's workers (make test) fill the slots, and a second suite beside it waits for a free one
# instead of running six robots on two cores, where tests miss deadlines no user would meet.
SYSTEM_TEST_SLOTS = range((os.cpu_count() or 1) + 1)
SLOT_DIR = Path(os.environ.get('OWL_TEST_SLOT_DIR', LEASE_DIR.parent / 'owl-kit-lab-test-slots'))
# And spare slots, each taken only while at least SPARE_IDLE of the machine's time was idle over the
# last spare_cpu.WINDOW (one test at a time takes slots; a spare at most every SPARE_SPACING, below):
# most system tests wait on discovery, timers and deadlines, and on a fast 2-core machine the slots
# above left a third of it idle (the suite 777 s; 676 s with a fourth test always allowed, no test
# slower to fail). Two spares lent at 15 % gave 612 s, no rerun; three, 629 s. Four (eight
# workers) gave 724 s: the tests' CPU grew with their wall time (kits and 3D pages that run longer
# cost more), 1,036 s against 876 s. A machine the suite keeps busy, as the slower 2-core ones,
# never lends them. OWL_TEST_SPARE_SLOTS and OWL_TEST_SPARE_IDLE change both (tests/test_reruns.py).
SPARE_SLOTS = range(len(SYSTEM_TEST_SLOTS), len(SYSTEM_TEST_SLOTS)
                    + int(os.environ.get('OWL_TEST_SPARE_SLOTS', '3')))
SPARE_IDLE = float(os.environ.get('OWL_TEST_SPARE_IDLE', '0.15'))
# The whole simulated kit (four modules, the camera rendering 30 frames/s), with more beside it (a
# tracker, robot_view's 3D page in Chromium): alone such a test keeps about one core busy (the robot
# view's controls: 62 s of CPU in 57 s). It holds two slots, so at most one other test runs beside it:
# beside two others a 3D page test ran three times slower, past its timeout.
WHOLE_KIT = 'whole_kit'
# One test at a time takes its slots, so two tests taking several never wait for each other's.
TAKING_SLOTS_DIR = SLOT_DIR / 'taking'
# The machine's idle share, sampled all along by each worker from its start; and spare
# slots lent at most one every SPARE_SPACING s, so the next is lent on a machine that already runs
# the last one's test (a look of its own at the machine each had taken WINDOW s: one spare test
# started every 2 s at most, where most system tests take less, and the workers waited 2,468 s for
# slots in a 596 s run while the machine was 21 % idle).
MACHINE_IDLE = IdleSampler() if SPARE_SLOTS else None
SPARE_SPACING = 0.5
LAST_SPARE_LENT = TAKING_SLOTS_DIR / 'last-spare-lent'


def wait_for_lock(directory: Path, ids: range) -> IO[str]:
    """The handle of one of ids' lock files in directory, once one is free; closing it frees it."""
    while (held := try_lock_file(directory, ids, os.getpid())) is None:
        time.sleep(0.1)
    return held[1]


def wait_for_slot() -> IO[str]:
    """The lock of a free one of SYSTEM_TEST_SLOTS, or of SPARE_SLOTS while the machine idles."""
    while True:
        held = try_lock_file(SLOT_DIR, SYSTEM_TEST_SLOTS, os.getpid())
        if held is None and MACHINE_IDLE and not spare_lent_lately():
            share = MACHINE_IDLE.share()
            if share is not None and share >= SPARE_IDLE:
                held = try_lock_file(SLOT_DIR, SPARE_SLOTS, os.getpid())
                if held is not None:
                    LAST_SPARE_LENT.touch()
        if held is not None:
            return held[1]
        time.sleep(0.1)


def spare_lent_lately() -> bool:
    """Whether any suite lent a spare slot in the last SPARE_SPACING s (asked while taking slots)."""
    try:
        return time.time() - LAST_SPARE_LENT.stat().st_mtime < SPARE_SPACING
    except FileNotFoundError:
        return False


def take_slots(held: ExitStack, count: int) -> None:
    """Wait for count slots (wait_for_slot), taken one test at a time; held keeps them till it closes."""
    with wait_for_lock(TAKING_SLOTS_DIR, range(1)):
        for _ in range(count):
            held.enter_context(wait_for_slot())


def build_lab_in_slots() -> None:
    """Build the class's lab (CLASS_LAB) while holding a whole_kit test's share of the slots."""
    import class_harness

    with ExitStack() as held:
        take_slots(held, min(2, len(SYSTEM_TEST_SLOTS)))
        class_harness.wait_for_lab()


# A test in tests/ that starts no process (the layout's, the course texts') loads the machine no more
# than a unit test: it holds no slot. 87 such tests had waited 178 s for slots in one run, each
# holding its worker back from the test after it.
NO_PROCESSES = 'no_processes'


def slots_needed(item: pytest.Item) -> int:
    """How many of SYSTEM_TEST_SLOTS a system test holds while it runs: its share of the machine."""
    if item.get_closest_marker(NO_PROCESSES):
        return 0
    if item.get_closest_marker(WHOLE_KIT):
        return min(2, len(SYSTEM_TEST_SLOTS))
    return 1


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_runtest_protocol(item: pytest.Item,
                            nextitem: pytest.Item | None) -> Generator[None, object, object]:
    """A system test runs (with its rerun, fixtures and timeout) only while it holds a slot.

    A test marked whole_kit holds two; one marked class_lab waits for the lab before it takes any.
    The waits are outside its timeout.
    """
    needed = slots_needed(item) if item.path.is_relative_to(SYSTEM_TESTS) else 0
    if not needed:
        return (yield)
    waiting_since = time.monotonic()
    if needs_class_lab(item):
        import class_harness

        class_harness.wait_for_lab()
    with ExitStack() as held:
        take_slots(held, needed)
        item.user_properties.append((suite_report.WAITED, time.monotonic() - waiting_since))
        return (yield)


@dataclass
class Rerun:
    first_failure: str
    outcome: str = 'passed'


# nodeid -> what a rerun test's first failure was and how its second run ended
RERUNS: dict[str, Rerun] = {}


# Where the controller writes each rerun test's whole first failure (traceback and the tails of its
# processes), one file per test: the summary line alone rarely tells a race's cause.
RERUN_REPORTS = SYSTEM_TESTS.parent / 'log' / 'reruns'
IN_WORKER = False  # True in a pytest-xdist worker, whose reports reach the controller


# Where a test that reaches its timeout leaves every thread's stack: the process's own stderr,
# taken before pytest captures it. pytest-timeout's own dump goes to the terminal, which in a
# pytest-xdist worker is /dev/null: the report then says only "worker 'gw1' crashed".
STACKS_AT_TIMEOUT: IO[str] | None = None


def pytest_configure(config: pytest.Config) -> None:
    global IN_WORKER, STACKS_AT_TIMEOUT
    for plugin in (suite_report, gates):  # for every test of the run, src/'s too
        if not config.pluginmanager.has_plugin(plugin.__name__):
            config.pluginmanager.register(plugin, plugin.__name__)
    IN_WORKER = hasattr(config, 'workerinput')
    if not IN_WORKER:
        shutil.rmtree(RERUN_REPORTS, ignore_errors=True)  # this run's reports only
    STACKS_AT_TIMEOUT = os.fdopen(os.dup(2), 'w')


GREENLET_STACKS_TIMER: threading.Timer | None = None


def dump_greenlet_stacks(out: IO[str]) -> None:
    """Write the stack of every suspended greenlet to out.

    Playwright's sync API runs the test in a greenlet and waits in another one's event loop: a
    thread dump shows only the loop, not the test line that waits for the page.
    """
    greenlet = sys.modules.get('greenlet')
    if greenlet is None:
        return
    for candidate in gc.get_objects():
        if isinstance(candidate, greenlet.greenlet) and candidate.gr_frame is not None:
            out.write('Greenlet (most recent call last):\n')
            out.write(''.join(traceback.format_stack(candidate.gr_frame)))
    out.flush()


@pytest.hookimpl(tryfirst=True)
def pytest_timeout_set_timer(item: pytest.Item, settings: Any) -> None:
    """Also dump every thread's and greenlet's stack to STACKS_AT_TIMEOUT before pytest-timeout ends the run.

    The greenlets' first (a Python thread, which needs the interpreter), then the threads' a second
    before the end (faulthandler, which does not). pytest-timeout's own timer is set after this
    (None lets it go on).
    """
    global GREENLET_STACKS_TIMER
    if STACKS_AT_TIMEOUT is not None:
        GREENLET_STACKS_TIMER = threading.Timer(max(settings.timeout - 2.0, 0.5), dump_greenlet_stacks,
                                                (STACKS_AT_TIMEOUT,))
        GREENLET_STACKS_TIMER.daemon = True
        GREENLET_STACKS_TIMER.start()
        faulthandler.dump_traceback_later(max(settings.timeout - 1.0, 0.5), file=STACKS_AT_TIMEOUT)


@pytest.hookimpl(tryfirst=True)
def pytest_timeout_cancel_timer(item: pytest.Item) -> None:
    if GREENLET_STACKS_TIMER is not None:
        GREENLET_STACKS_TIMER.cancel()
    faulthandler.cancel_dump_traceback_later()


def rerun_report_path(nodeid: str) -> Path:
    return RERUN_REPORTS / (re.sub(r'[^\w.-]+', '_', nodeid) + '.txt')


def write_rerun_report(report: pytest.TestReport) -> None:
    sections = ''.join(f'\n----- {title} -----\n{content}\n' for title, content in report.sections)
    path = rerun_report_path(report.nodeid)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f'{report.nodeid} ({report.when})\n\n{report.longreprtext}\n{sections}')


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    # pytest types outcome as passed/failed/skipped; pytest-rerunfailures sets 'rerun' too
    if report.outcome == 'rerun' and report.nodeid not in RERUNS:  # type: ignore[comparison-overlap]
        # The call's report, then a failed teardown's: keep the first.
        RERUNS[report.nodeid] = Rerun(first_line(report))
        if not IN_WORKER:
            write_rerun_report(report)
    elif report.nodeid in RERUNS and (report.when == 'call' or not report.passed):
        RERUNS[report.nodeid].outcome = report.outcome


# A line naming a raised exception, as a traceback ends: "RuntimeError: ...", "[node-1] SystemError: ..."
RAISED = re.compile(r'\b[A-Z]\w*(Error|Exception|Interrupt): ')


def first_line(report: pytest.TestReport) -> str:
    """A failure report's exception in one line, as in pytest's short test summary.

    When the assertion's message is a process's output (a launch's starts with its log folder), the last
    exception that output names says more than its first line, so that one is shown.
    """
    crash = getattr(report.longrepr, 'reprcrash', None)
    text = crash.message if crash is not None else report.longreprtext
    lines = [line.strip() for line in text.splitlines() if line.strip()] or ['(no message)']
    line = lines[0]
    raised = [later for later in lines[1:] if RAISED.search(later)]
    if raised:
        kind = re.match(r'[\w.]+: ', line)
        line = f'{kind.group(0) if kind else ""}... {raised[-1]}'
    return line if len(line) <= 300 else line[:297] + '...'


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> Generator[None, None, None]:
    """A flake is never silent: one line per test that needed its second run, after every other summary.

    The lines come just above the final counts line, which CI reads.
    """
    result = yield
    if RERUNS:
        terminalreporter.write_line(
            f'first failures of rerun tests, in full: {os.path.relpath(RERUN_REPORTS)}/')
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
