"""turtle_teleop_key driven through a pseudo-terminal, against a real turtlesim_node."""

from __future__ import annotations

import os
import pty
import select
import signal
import subprocess
import termios
import threading
import time
from collections.abc import Callable
from pathlib import Path

import pytest
from geometry_msgs.msg import Twist
from owl_common.processes import dies_with_this_process, installed_executable
from owl_common.run import TEARDOWN_LIMIT
from ros_harness import wait_until, with_hung_teardown
from turtlesim.msg import Pose

BANNER = """Reading from keyboard
---------------------------
Use arrow keys to move the turtle.
Use G|B|V|C|D|E|R|T keys to rotate to absolute orientations. 'F' to cancel a rotation.
'Q' to quit."""


class TerminalProcess:
    """A command whose stdin/stdout/stderr are the slave side of a fresh pseudo-terminal."""

    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        self.master, self.slave = pty.openpty()
        self.mode_before = termios.tcgetattr(self.slave)
        self.popen = subprocess.Popen(argv, env=env, stdin=self.slave, stdout=self.slave,
                                      stderr=self.slave, start_new_session=True,
                                      preexec_fn=dies_with_this_process())
        self._chunks: list[bytes] = []
        self._stop = threading.Event()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        # Short selects, so hang_up() can stop this thread before closing the descriptors.
        while not self._stop.is_set():
            if not select.select([self.master], [], [], 0.05)[0]:
                continue
            try:
                data = os.read(self.master, 4096)
            except OSError:
                return
            if not data:
                return
            self._chunks.append(data)

    @property
    def output(self) -> str:
        return b''.join(self._chunks).decode(errors='replace').replace('\r\n', '\n')

    def type(self, keys: str) -> None:
        os.write(self.master, keys.encode())

    def hang_up(self) -> None:
        """Close our ends of the terminal, as closing a terminal window does."""
        self._stop.set()
        self._reader.join(5)
        for fd in (self.master, self.slave):
            if fd >= 0:
                os.close(fd)
        self.master = self.slave = -1

    def close(self) -> None:
        if self.popen.poll() is None:
            os.killpg(self.popen.pid, signal.SIGKILL)
            self.popen.wait(5)
        self.hang_up()


@pytest.fixture
def terminal(ros):
    started: list[TerminalProcess] = []

    def start(wrap: Callable[[Path], list[str]] = lambda teleop: [str(teleop)]) -> TerminalProcess:
        process = TerminalProcess(wrap(installed_executable('turtlesim', 'turtle_teleop_key')), ros.env)
        started.append(process)
        wait_until(lambda: BANNER in process.output, 30, 'the teleop banner')
        return process

    yield start
    for process in started:
        process.close()


def test_not_a_terminal_is_one_line_and_exit_2(ros):
    teleop = ros.run('turtlesim', 'turtle_teleop_key')
    assert teleop.wait(timeout=30) == 2
    assert len(teleop.lines) == 1
    assert 'not a terminal' in teleop.lines[0]


def test_keys_publish_twists_and_goals_and_q_restores_the_terminal(ros, terminal):
    sim = ros.run('turtlesim', 'turtlesim_node', '--headless')
    sim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    twists = ros.probe.collect(Twist, '/turtle1/cmd_vel', 10)
    poses = ros.probe.collect(Pose, '/turtle1/pose', 7)
    teleop = terminal()
    ros.probe.wait_for_node('teleop_turtle')
    wait_until(lambda: ros.probe.node.count_publishers('/turtle1/cmd_vel') == 1, 10, 'teleop publisher')
    # Until teleop's publisher has matched the probe, a key's Twist can be lost: press Up until
    # one gets through, then start counting.
    for _ in range(40):
        teleop.type('\x1b[A')
        time.sleep(0.25)
        if twists:
            break
    assert twists
    assert twists[-1].linear.x == 2.0  # up
    time.sleep(0.25)
    twists.clear()

    def press(keys: str, count: int) -> Twist:
        teleop.type(keys)
        wait_until(lambda: len(twists) >= count, 10, f'Twist for {keys!r}')
        return twists[-1]

    assert press('\x1b[A', 1).linear.x == 2.0  # up
    down = press('\x1b[B', 2)
    assert (down.linear.x, down.angular.z) == (-2.0, 0.0)
    assert press('\x1b[D', 3).angular.z == 2.0  # left
    right = press('\x1b[C', 4)
    assert (right.linear.x, right.linear.y, right.linear.z, right.angular.x, right.angular.y,
            right.angular.z) == (0.0, 0.0, 0.0, 0.0, 0.0, -2.0)
    teleop.type('xyz')  # unknown keys: nothing
    (result,) = ros.probe.set_parameters('teleop_turtle', scale_linear=0.5)
    assert result.successful
    for wrong in ({'scale_linear': 'fast'}, {'scale_angular': True}):
        (result,) = ros.probe.set_parameters('teleop_turtle', **wrong)
        assert not result.successful
    assert ros.probe.get_parameters('teleop_turtle', 'scale_angular') == [2.0]
    assert press('\x1b[A', 5).linear.x == 0.5
    assert len(twists) == 5
    # turtlesim aborts a rotation goal at any velocity command it takes while the goal runs (as
    # upstream's): the probe had this Twist, turtlesim maybe not yet, so wait until it moves with it.
    wait_until(lambda: any(pose.linear_velocity == 0.5 for pose in poses), 10, 'turtle1 moving at 0.5')

    teleop.type('r')  # rotate to 1.5708
    sim.wait_for(r'Rotation goal completed successfully', timeout=15)
    wait_until(lambda: poses[-1].angular_velocity == 0.0, 10, 'turtle1 done turning')
    assert abs(poses[-1].theta - 1.5708) < 0.02  # r is the key straight above f
    teleop.type('d')  # a long turn; f cancels it once it is under way (teleop holds its handle)
    wait_until(lambda: poses[-1].angular_velocity == 1.0, 10, 'turtle1 turning towards d')
    teleop.type('f')
    sim.wait_for(r'Rotation goal canceled', timeout=15)

    teleop.type('q')
    assert teleop.popen.wait(15) == 0
    assert termios.tcgetattr(teleop.slave) == teleop.mode_before
    assert 'Traceback' not in teleop.output


@pytest.mark.parametrize('sig', [signal.SIGINT, signal.SIGTERM])
def test_ctrl_c_or_term_exits_cleanly_and_restores_the_terminal(ros, terminal, sig):
    teleop = terminal()
    raw = termios.tcgetattr(teleop.slave)
    assert not raw[3] & termios.ICANON
    assert not raw[3] & termios.ECHO
    os.killpg(teleop.popen.pid, sig)
    assert teleop.popen.wait(15) == 0
    assert termios.tcgetattr(teleop.slave) == teleop.mode_before
    assert 'Traceback' not in teleop.output


def test_terminal_hang_up_ends_teleop_instead_of_spinning(ros, terminal):
    teleop = terminal()
    teleop.hang_up()
    assert teleop.popen.wait(15) == 0


def test_a_hung_clean_up_ends_teleop_with_every_stack(ros, terminal):
    teleop = terminal(with_hung_teardown)
    os.killpg(teleop.popen.pid, signal.SIGINT)
    assert teleop.popen.wait(TEARDOWN_LIMIT + 3) == 1, teleop.output
    wait_until(lambda: 'in destroy_node' in teleop.output, 5, 'the stack of the hung clean-up')
    assert 'Timeout (0:00:05)!' in teleop.output
