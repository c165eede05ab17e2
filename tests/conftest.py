import os

import pytest

# Set before any rclpy context exists in this process.
os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'

from ros_harness import RosHarness


@pytest.fixture
def ros():
    """Processes and a probe node in a ROS domain that no other test or run shares."""
    harness = RosHarness()
    try:
        yield harness
    finally:
        harness.close()


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
