"""The course's listings, typed verbatim, end every Ctrl-C cleanly on Jazzy (owl_rclpy_repair.py).

tests/course_listings/ holds each listing of the course as a student types it (see its README). Each
runs in a private domain beside what it talks to, and gets one Ctrl-C (SIGINT to its process group,
as a terminal sends it) at a random moment between its node's appearance in the graph and 1.5 s
later (4 s for the appendix's, whose constructor waits for two services: within 1.5 s, 2-3 of 20
runs got past it, and 1 test in about 10 saw none; within 4 s, 6-7): inside the rest of its
constructor, its spin, its callbacks, its service wait. 12 runs per listing, RUNS_AT_ONCE at a
time, each at a random moment of its own twelfth of that window (stratified: 20 uniform draws, as
before, left gaps of up to a fifth of the window; 12 strata leave none wider than two twelfths).
Each run must end with exit code 0 and print no traceback. Every other copy also gets the
copy of the Ctrl-C that `ros2 launch` passes on, DOUBLE_PRESS s later: the appendix's torque-off
must still happen. A run still alive EXIT_TIMEOUT s after its Ctrl-C fails with every thread's
stack (faulthandler).

On Jazzy's rclpy without the repair, every listing fails: the ones with no try/except (3.5.x,
3.6.3, 3.7.2) print a KeyboardInterrupt or ExternalShutdownException traceback, and the
appendix's ends with "RCLError: failed to shutdown: rcl_shutdown already called" after a
torque-off call that never reached the servo.
"""

from __future__ import annotations

import random
import re
import signal
import subprocess
import time
from dataclasses import dataclass

import course_lines
import pytest
from owl_common.processes import RosProcess
from ros_harness import RosHarness, wait_until
from servo_helpers import start_servo

RUNS = 12
RUNS_AT_ONCE = 4
LATEST_CTRL_C = 1.5  # s after the node appeared
EXIT_TIMEOUT = 10.0
DOUBLE_PRESS = 0.01  # s
TRACEBACK = re.compile(r'Traceback|Error|Exception ignored')
# Fast DDS's shared-memory transport logs this at start when a port's segment is gone or unfinished
# while another process still holds the port's lock (one starting or ending at that moment); the
# participant then takes the next port and works. It is the middleware's, before any Ctrl-C, and a
# real install prints it too (eProsima/Fast-DDS#2003); seen once in 20 suite runs.
FASTDDS_SHM_PORT_TAKEN = re.compile(
    r'^.*RTPS_TRANSPORT_SHM.*Failed init_port fastrtps_port\d+: open_and_lock_file failed.*$\n?', re.M)


@dataclass
class Listing:
    script: str
    node: str
    args: tuple[str, ...] = ()
    beside: tuple[str, ...] = ()  # other listings that run during the test (the other end of a topic)
    servo: str | None = None  # a simulated kit servo it talks to
    latest_ctrl_c: float = LATEST_CTRL_C


CASES = [
    Listing('s3_5_1_publisher.py', 'my_publisher'),
    Listing('s3_5_2_subscriber.py', 'my_subscriber', beside=('s3_5_1_publisher.py',)),
    Listing('s3_5_3_random_number_publisher.py', 'random_number_publisher'),
    Listing('s3_5_4_random_number_subscriber.py', 'random_number_subscriber',
            beside=('s3_5_3_random_number_publisher.py',)),
    Listing('s3_6_3_service_temperature.py', 'temp_service'),
    # No server: the Ctrl-C lands in the constructor's wait_for_service loop, as when a student
    # starts the client first and gives up waiting.
    Listing('s3_6_3_client_temperature.py', 'temp_client', args=('0.0',)),
    Listing('s3_7_2_random_number_publisher_parameter.py', 'random_number_publisher'),
    Listing('s5_3_pid_testing.py', 'control_servo', servo='pan', latest_ctrl_c=4.0),
    Listing('tutorial_action_server.py', 'rotate_action_server', beside=('tutorial_action_client.py',)),
    Listing('tutorial_parameter_node.py', 'parameter_node'),
]


def run_once(ros: RosHarness, listing: Listing, round_number: int,
             delays: list[float]) -> list[tuple[RosProcess, float]]:
    """Start len(delays) copies of the listing; give each its Ctrl-C delays[i] s after its node appeared.

    Each copy's node gets a name of its own (`--ros-args -r __node:=...`, which rclpy.init() reads
    from the command line as it would a student's), so a copy is known to be up by its own name,
    whatever the graph still remembers of the last round.
    """
    names = [f'{listing.node}_{round_number}_{index}' for index in range(len(delays))]
    started = [ros.command(['python', str(course_lines.LISTINGS / listing.script), *listing.args,
                            '--ros-args', '-r', f'__node:={name}'],
                           label=f'{listing.script} #{index}', env={'PYTHONFAULTHANDLER': '1'})
               for index, name in enumerate(names)]
    appeared: dict[str, float] = {}

    def all_appeared() -> bool:
        now = time.monotonic()
        for name in set(ros.probe.node.get_node_names()) & set(names):
            appeared.setdefault(name, now)
        return len(appeared) == len(names)

    wait_until(all_appeared, 20.0, f'{len(names)} {listing.node} nodes')
    moments = sorted((appeared[name] + delay, index, process)
                     for index, (name, delay, process) in enumerate(zip(names, delays, started, strict=True)))
    for moment, index, process in moments:
        time.sleep(max(0.0, moment - time.monotonic()))
        process.send_signal()
        if index % 2:
            time.sleep(DOUBLE_PRESS)
            process.send_signal()
    for process in started:
        try:
            process.wait(EXIT_TIMEOUT)
        except subprocess.TimeoutExpired:
            process.send_signal(signal.SIGABRT)  # faulthandler prints where each thread is
            process.wait(EXIT_TIMEOUT)
    return list(zip(started, delays, strict=True))


def ctrl_c_moments(rng: random.Random, latest: float) -> list[float]:
    """RUNS moments in [0, latest): one at random in each of RUNS equal strata, in a random order.

    The order spreads each round's copies over the window, so no round is all early or all late.
    """
    moments = [(stratum + rng.random()) * latest / RUNS for stratum in range(RUNS)]
    rng.shuffle(moments)
    return moments


def test_the_ctrl_c_moments_cover_the_window_one_per_stratum():
    latest = 1.5
    moments = ctrl_c_moments(random.Random(7), latest)
    assert sorted(int(moment * RUNS / latest) for moment in moments) == list(range(RUNS))


@pytest.mark.parametrize('listing', CASES, ids=[c.script.removesuffix('.py') for c in CASES])
def test_ctrl_c_at_any_moment_ends_a_listing_cleanly(ros: RosHarness, listing: Listing):
    servo = start_servo(ros, listing.servo) if listing.servo else None
    for other in listing.beside:
        ros.command(['python', str(course_lines.LISTINGS / other)], label=other)
    delays = ctrl_c_moments(random.Random(), listing.latest_ctrl_c)
    failures = []
    for round_number in range(RUNS // RUNS_AT_ONCE):
        at_once = delays[round_number * RUNS_AT_ONCE:(round_number + 1) * RUNS_AT_ONCE]
        for process, delay in run_once(ros, listing, round_number, at_once):
            code = process.popen.returncode
            if code != 0 or TRACEBACK.search(FASTDDS_SHM_PORT_TAKEN.sub('', process.output)):
                failures.append(f'Ctrl-C {delay:.2f} s after its node appeared: exit code {code}, '
                                f'output:\n{process.tail(60)}')
    assert not failures, f'{len(failures)} of {RUNS} runs did not end cleanly; the first:\n{failures[0]}'
    if servo is not None:
        # The appendix's except clause switches the torque off whenever it had been switched on.
        enabled = len(re.findall(r'torque enabled', servo.output))
        assert enabled > 0, 'no run got as far as enabling the torque'
        wait_until(lambda: len(re.findall(r'torque disabled', servo.output)) == enabled, 5.0,
                   f'{enabled} torque-off calls')


def test_the_listings_are_the_courses_own_lines():
    """Each line of a listing is a line of the course (tests/course_lines.py).

    A clean clone has the digests of the course's lines that the listings use; where the course
    is beside the clone, those digests are also checked against the course itself.
    """
    stored = course_lines.stored_digests()
    for name, lines in course_lines.listing_lines().items():
        foreign = [line for line in lines if course_lines.digest(line) not in stored]
        assert not foreign, f'{name}: not in the course: {foreign}'
    if course_lines.COURSE.is_dir():
        assert sorted(stored) == course_lines.digests_from_course(course_lines.COURSE), (
            f'{course_lines.DIGESTS} is not what the course gives: python tests/course_lines.py')
