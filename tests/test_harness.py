"""The shared sandbox leaves its domain as it found it, and reports unclean stops usefully."""

import signal
import socket
import subprocess

import pytest
from owl_common.processes import ROS2_DAEMON_BASE_PORT, RosSandbox, installed_executable
from owl_common.run import TEARDOWN_LIMIT
from ros_harness import Probe, wait_until, with_hung_teardown


def daemon_listening(domain_id: int) -> bool:
    try:
        socket.create_connection(('127.0.0.1', ROS2_DAEMON_BASE_PORT + domain_id), timeout=0.2).close()
    except OSError:
        return False
    return True


def test_closing_a_sandbox_stops_the_ros2_daemon_of_its_domain():
    with RosSandbox() as sandbox:
        domain_id = sandbox.domain_id
        started = subprocess.run(['ros2', 'daemon', 'start'], env=sandbox.env, capture_output=True,
                                 text=True, timeout=30)
        assert started.returncode == 0, started.stderr
        assert daemon_listening(domain_id)
    assert not daemon_listening(domain_id)


def test_processes_of_a_closed_sandbox_are_gone():
    with RosSandbox() as sandbox:
        sleeper = sandbox.command(['sleep', '60'])
    assert not sleeper.running()


# A test run as a separate process: it starts turtlesim in a sandbox, says turtlesim's pid, then waits.
KILLED_RUNNER = """
import time
from owl_common.processes import RosSandbox

sandbox = RosSandbox()
turtlesim = sandbox.run('turtlesim', 'turtlesim_node', '--headless')
turtlesim.wait_for(r'Spawning turtle', timeout=30)
print('turtlesim', turtlesim.pid, flush=True)
time.sleep(120)
"""


def pid_alive(pid: int) -> bool:
    try:
        with open(f'/proc/{pid}/stat') as stat:
            return stat.read().split(') ', 1)[1][0] != 'Z'
    except FileNotFoundError:
        return False


@pytest.mark.parametrize('kill_signal', [signal.SIGKILL, signal.SIGTERM])
def test_a_killed_test_run_takes_its_ros_processes_with_it(kill_signal, tmp_path):
    (tmp_path / 'runner.py').write_text(KILLED_RUNNER)
    with RosSandbox() as outer:  # only for its domain and environment
        runner = outer.command(['python', str(tmp_path / 'runner.py')], label='runner')
        turtlesim_pid = int(runner.wait_for(r'^turtlesim (\d+)', timeout=40)[0].group(1))
        assert pid_alive(turtlesim_pid)
        runner.popen.send_signal(kill_signal)
        runner.popen.wait(timeout=10)
        wait_until(lambda: not pid_alive(turtlesim_pid), 10, f'turtlesim {turtlesim_pid} to end with the run')


def test_stop_cleanly_reports_the_exit_code_signal_and_output_of_an_unclean_stop():
    with RosSandbox() as sandbox:
        stubborn = sandbox.command(['sh', '-c', 'trap "echo cleaning up; exit 3" INT; echo ready; '
                                   'while :; do sleep 0.05; done'])
        stubborn.wait_for('ready')
        with pytest.raises(AssertionError) as failure:
            stubborn.stop_cleanly()
    assert 'exit code 3 after SIGINT' in str(failure.value)
    assert 'cleaning up' in str(failure.value)


def test_children_stop_on_ctrl_c_even_when_the_runner_ignores_it():
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)  # as under `nohup` or `make test &`
    try:
        with RosSandbox() as sandbox:
            sleeper = sandbox.command(['sleep', '60'])
            assert sleeper.stop(timeout=5) == -signal.SIGINT
            assert sleeper.last_signal == signal.SIGINT
    finally:
        signal.signal(signal.SIGINT, previous)


def test_a_node_whose_clean_up_hangs_ends_itself_with_every_stack():
    # The CLI tests' talker runs on owl_common.run.spin_node, which has the watchdog (the course's own
    # packages use plain rclpy calls instead, so a student can compare them with the listings).
    talker = installed_executable('ros2cli_test_fixtures', 'talker')
    with RosSandbox() as sandbox:
        node = sandbox.command(with_hung_teardown(talker), label='talker')
        probe = Probe(sandbox.domain_id)
        try:  # in the graph: spinning, so Ctrl-C now starts spin_node's clean-up
            wait_until(lambda: 'talker' in probe.node.get_node_names(), 30, 'the talker node')
        finally:
            probe.close()
        node.send_signal(signal.SIGINT)
        assert node.wait(timeout=TEARDOWN_LIMIT + 3) == 1, node.tail()
        # The watchdog's dump of every thread (here the hang is the wrapper's exit-time one).
        assert 'Timeout (0:00:05)!' in node.output, node.tail()
        assert 'most recent call first' in node.output, node.tail()
