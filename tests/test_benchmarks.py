"""Every benchmark still runs: each one, shrunk to a few seconds, exits 0 and prints its numbers.

Only that they run is checked here; their numbers are for `make bench` and the closing notes (timing
assertions would be flaky on a shared machine and belong in bench/, not in tests).
"""

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from gates import prerequisite_missing
from web_harness import chromium_missing

BENCH = Path(__file__).resolve().parents[1] / 'bench'
BENCH_TIMEOUT = 110.0  # s: under the test's own 120 s, so a hang fails here with its stacks
# drive the robot view's page as the browser tests do
NEEDS_CHROMIUM = {'front_door.py', 'robot_view_latency.py', 'robot_view_smoothness.py'}
# A class server with a student's kit: root's (it makes accounts), a whole kit's share of the machine,
# and the time to build the students' lab when no class test has built it yet.
CLASS_SERVER, CLASS_SERVER_TIMEOUT = 'class_server.py', 330.0
SHRUNK = {
    'bag_record.py': ['--seconds', '0.5'],
    CLASS_SERVER: ['--students', '1', '--seconds', '1'],
    'dds_discovery.py': ['--runs', '1', '--nodes', '2', '--periods', '200', '--idle-seconds', '0.2',
                         '--settle-seconds', '0'],
    'front_door.py': ['--requests', '5', '--messages', '5', '--seconds', '0.5', '--warm-up', '0'],
    'launch_timings.py': ['--repeat', '1'],
    'olive_sim_cpu.py': ['--seconds', '0.3', '--warmup', '0', '--camera-seconds', '0.3'],
    'owl_check_timings.py': ['--exercises', 'currency_server', '--kit-runs', '1'],
    'robot_view_latency.py': ['--samples', '1', '--pause', '0.3'],
    'robot_view_smoothness.py': ['--seconds', '0.5'],
    'ros2_help.py': ['--runs', '1'],
    'ros2cli_graph.py': ['--runs', '1', '--seconds', '0.5', '--messages', '200'],
    'service_roundtrip.py': ['--calls', '20', '--long-calls', '100'],
    'stop_stress.py': ['--stops', '1', '--hogs', '0', '--kinds', 'temp_server ALL'],
    'teardown_hangs.py': ['--pairs', '1', '--hogs', '0'],
    'turtlesim_pose_rate.py': ['--seconds', '0.3'],
}


def test_every_benchmark_has_a_shrunk_run():
    scripts = {path.name for path in BENCH.glob('*.py')} - {'measure.py'}
    assert scripts == set(SHRUNK)


def marks_of(script: str) -> list[pytest.MarkDecorator]:
    if script == CLASS_SERVER:
        return [pytest.mark.whole_kit, pytest.mark.class_lab, pytest.mark.timeout(CLASS_SERVER_TIMEOUT + 10)]
    return [pytest.mark.whole_kit] if script in NEEDS_CHROMIUM else []


@pytest.mark.parametrize('script', [pytest.param(name, marks=marks_of(name)) for name in sorted(SHRUNK)])
def test_benchmark_runs(script):
    if script in NEEDS_CHROMIUM and (missing := chromium_missing()):
        prerequisite_missing(missing)
    if script == CLASS_SERVER and os.geteuid() != 0:
        prerequisite_missing('the class server bench makes Unix accounts: it runs as root')
    timeout = CLASS_SERVER_TIMEOUT if script == CLASS_SERVER else BENCH_TIMEOUT
    result = run_benchmark([str(BENCH / script), *SHRUNK[script]], timeout)
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'Traceback' not in result.stderr
    assert any(character.isdigit() for character in result.stdout), result.stdout


def run_benchmark(argv: list[str], timeout: float) -> subprocess.CompletedProcess:
    """Run a Python script; past timeout, fail with its output and every thread's stack.

    A benchmark that hangs is ended with SIGABRT, which Python's faulthandler (PYTHONFAULTHANDLER)
    answers by printing where each thread waits: a SIGKILL would leave only "timed out".
    """
    command = [sys.executable, *argv]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          env={**os.environ, 'PYTHONFAULTHANDLER': '1'}) as process:
        try:
            stdout, stderr = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            process.send_signal(signal.SIGABRT)
            try:
                stdout, stderr = process.communicate(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                stdout, stderr = process.communicate()
            pytest.fail(f'{Path(argv[0]).name} ran past {timeout} s; its output, then its stacks:\n'
                        f'{stdout}{stderr}', pytrace=False)
    return subprocess.CompletedProcess(command, process.returncode, stdout, stderr)


def test_a_benchmark_past_its_time_fails_with_the_stack_it_waits_in(tmp_path):
    script = tmp_path / 'hangs.py'
    script.write_text('import time\nprint("started", flush=True)\n'
                      'def wait_for_the_page():\n    time.sleep(60)\nwait_for_the_page()\n')
    with pytest.raises(pytest.fail.Exception) as failure:
        run_benchmark([str(script)], 2.0)
    assert 'started' in str(failure.value)
    assert 'in wait_for_the_page' in str(failure.value)


@pytest.mark.parametrize('argv', [['--calls', '0'], ['--long-calls', '5'], ['--long-calls', 'many']])
def test_service_roundtrip_refuses_counts_it_cannot_measure_in_one_line(argv):
    result = subprocess.run([sys.executable, str(BENCH / 'service_roundtrip.py'), *argv], capture_output=True,
                            text=True, timeout=30, check=False)
    assert result.returncode == 2
    assert 'Traceback' not in result.stderr
    assert result.stderr.splitlines()[-1].startswith('service_roundtrip.py: error: argument --')
