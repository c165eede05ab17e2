"""How a node's main() answers Ctrl-C: the course's plain rclpy shape, in variants, and the installed nodes.

One private ROS domain holds olive_sim's imu_sim (scripted motion, so imu_turtle's callbacks run
all the time) and the pan servo_sim. Each kind of node below is started and stopped with SIGINT
again and again, kinds interleaved so all see the same machine load:
- steady stops: SIGINT a random 0..0.5 s after the node says it is working (imu_turtle drives,
  control_servo has its torque on);
- start-up stops: SIGINT a random time between the start and the node's usual time to get working
  (the median so far), so it lands anywhere in imports, rclpy.init, construction or the first spins.
Each stop is classified: clean (exit 0, no "Traceback" and no "Exception ignored" in the output
and, for a servo node that got its torque on, "torque disabled" logged), traceback (exit 0 but one
of those two words), torque left on, watchdog (owl_common.run's teardown watchdog fired: exit 1
and a stack dump), alive (still running 8 s after the SIGINT: native stacks shown, then killed),
interrupted before main() (a KeyboardInterrupt traceback from the imports, or a SIGINT before
Python has its handler, as any Python program, whatever its main() does), or exit N / SIGNAL
(anything else). The first output of each kind that is not clean is printed.

The kinds: `imu_turtle`, `control_servo` are the installed executables, whatever main() they
have. The others are a node class of ours run by course_main() below, a main() of the course's shape
(plain rclpy.init / rclpy.spin / destroy_node / try_shutdown) in variants: `... course` builds the
node before the `try`, the others inside it; `ALL` keeps rclpy's own Ctrl-C handler (plain
`rclpy.init(args=args)`), `NO` passes signal_handler_options=SignalHandlerOptions.NO; `polling`
spins in 0.1 s spin_once calls; `quiet` sets Python's SIGINT handler to SIG_IGN so only rclpy's
acts; `guard` calls owl_common.run.interrupt_between_callbacks-style code (Ctrl-C triggers a guard
condition whose callback raises KeyboardInterrupt); `owl_common.run` is the stop-request main()
the nodes had before. By default the installed nodes run, with `imu_turtle ALL` as the baseline:
the same node with rclpy's own handler. --flood adds a process publishing IMU messages as fast as
it can, so imu_turtle takes a message most of the time (an accelerated test of the Ctrl-C that
lands while rclpy builds a message).
--hogs busy-loop processes compete for the CPU during the whole run.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import signal
import statistics
import sys
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import cast

import rclpy
from olive_imu.imu_turtle import DEFAULT_IMU_TOPIC, ImuTurtle
from olive_servo.control_servo import ControlServo
from olive_servo.pid_testing import PidTesting
from olive_srvcli.service_temperature import TempService
from owl_common.processes import RosProcess, RosSandbox
from owl_common.run import begin_cleanup, init_with_stop_request, spin_until_stopped
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from rclpy.signals import SignalHandlerOptions
from sensor_msgs.msg import Imu
from teardown_hangs import HOG, native_stacks, upper_bound, version

KILL_AFTER = 8.0   # s after the SIGINT: still running by then is a hang
POLL = 0.01        # s
STEADY_DELAY = (0.0, 0.5)  # s after the node says it works
FIRST_STARTUP_GUESS = 1.5  # s: the start-up window before any start was measured
SHOWN_LINES = 40
CHILD_READY = r'^spinning$'  # the children's line just before they spin
IMU_READY = r'IMU data on .*: driving'
SERVO_READY = r'torque enabled: pan'
BAD_WORDS = ('Traceback', 'Exception ignored')
BEFORE_MAIN = 'interrupted before main()'
NOT_COUNTED = ('clean', BEFORE_MAIN)  # neither is the main()'s fault
# A traceback frame of a node's main() (not of site.main, which runs before any of our code).
MAIN_FRAME = re.compile(r', in course_\w+$|/olive_\w+/\w+\.py", line \d+, in main$', re.MULTILINE)
SERVO_PARAMETERS = ['-p', 'min_position:=-1.5708', '-p', 'max_position:=1.5708']
TorqueNode = ControlServo | PidTesting  # the nodes course_main(..., torque=True) runs


def course_main(make_node: Callable[[], Node], options: SignalHandlerOptions, construct_in_try: bool,
                spin: Callable[[Node], None] = rclpy.spin, torque: bool = False, quiet: bool = False,
                guard: bool = False) -> None:
    """A node's main() in the course's shape, in the variants measured here.

    construct_in_try False is the shape of common.md (the node is built before the try); True
    builds it inside the try, so a Ctrl-C during construction is caught too. torque: enable the
    torque before spinning and disable it in the clean-up, as the servo nodes do. quiet: Python's
    own SIGINT handler is SIG_IGN, so Ctrl-C only shuts ROS down (rclpy's handler) and rclpy.spin
    returns or raises ExternalShutdownException; there is no KeyboardInterrupt. guard: once the node
    is built, Ctrl-C only triggers a guard condition of the node whose callback raises
    KeyboardInterrupt, so it leaves rclpy.spin between two callbacks, never from Python code that
    rclpy's C++ calls (a message's constructor while a message is taken).
    """
    if quiet:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # rclpy's handler alone: no KeyboardInterrupt
    rclpy.init(signal_handler_options=options)
    node = None if construct_in_try else make_node()
    try:
        if node is None:
            node = make_node()
        if guard:
            stop = node.create_guard_condition(raise_keyboard_interrupt)
            signal.signal(signal.SIGINT, lambda signum, frame: stop.trigger())
        if torque:
            cast(TorqueNode, node).enable_torque()
        print('spinning', flush=True)
        spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            if torque:
                cast(TorqueNode, node).disable_torque()
            node.destroy_node()
        rclpy.try_shutdown()


def owl_common_main(make_node: Callable[[], Node]) -> None:
    """The main() the course's nodes had before: owl_common.run's stop request and teardown watchdog.

    The stop request never raises inside rclpy while it spins; it polls every 0.1 s.
    """
    stop = init_with_stop_request()
    node = None
    try:
        node = make_node()
        print('spinning', flush=True)
        spin_until_stopped(node, stop)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        begin_cleanup()
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()


def flood_imu() -> None:
    """Publish a level IMU's messages on imu_turtle's topic as fast as Python can (--flood).

    The nodes then take a message most of the time, where a KeyboardInterrupt can land in rclpy.
    """
    rclpy.init()
    node = Node('imu_flood')
    publisher = node.create_publisher(Imu, DEFAULT_IMU_TOPIC, qos_profile_sensor_data)
    msg = Imu()
    msg.orientation.w = 1.0
    try:
        while True:
            publisher.publish(msg)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


def raise_keyboard_interrupt() -> None:
    """The `guard` variant's guard condition callback: Ctrl-C leaves rclpy.spin between two callbacks."""
    raise KeyboardInterrupt


def spin_polling(node: Node) -> None:
    """rclpy.spin in short waits, so a Ctrl-C with rclpy's handler off is seen within 0.1 s."""
    while rclpy.ok():
        rclpy.spin_once(node, timeout_sec=0.1)


DEFAULT_KINDS = 'imu_turtle,control_servo,imu_turtle ALL'
ALL, NO = SignalHandlerOptions.ALL, SignalHandlerOptions.NO
CHILDREN: dict[str, Callable[[], None]] = {
    # run 1: the shape of common.md as it stands
    'imu_turtle course': lambda: course_main(ImuTurtle, ALL, False),
    'control_servo course': lambda: course_main(ControlServo, NO, False, torque=True),
    # run 2: the node built inside the try; rclpy's handler off (NO) or on (ALL)
    'imu_turtle NO': lambda: course_main(ImuTurtle, NO, True),
    'imu_turtle ALL': lambda: course_main(ImuTurtle, ALL, True),
    'control_servo NO': lambda: course_main(ControlServo, NO, True, torque=True),
    'pid_testing NO': lambda: course_main(PidTesting, NO, True, torque=True),
    'pid_testing NO polling': lambda: course_main(PidTesting, NO, True, spin_polling, torque=True),
    'imu_turtle ALL quiet': lambda: course_main(ImuTurtle, ALL, True, quiet=True),
    'imu_turtle NO guard': lambda: course_main(ImuTurtle, NO, True, guard=True),
    'imu_turtle owl_common.run': lambda: owl_common_main(ImuTurtle),
    'flood': flood_imu,
    'temp_server ALL': lambda: course_main(TempService, ALL, True),
    'temp_server NO': lambda: course_main(TempService, NO, True),
}


@dataclass
class Kind:
    """A kind of node under test: how to start it, the line saying it works, and its results so far.

    servo: check that a torque it enabled is disabled again. counts: the outcomes by phase ('steady',
    'start-up'); shown: the outcomes whose first output has been printed already.
    """

    label: str
    start: Callable[[RosSandbox], RosProcess]
    ready: str
    servo: bool
    ready_times: list[float] = field(default_factory=list)
    counts: dict[str, Counter[str]] = field(
        default_factory=lambda: {'steady': Counter(), 'start-up': Counter()})
    stop_times: list[float] = field(default_factory=list)
    shown: set[str] = field(default_factory=set)

    def startup_window(self) -> float:
        """Seconds the kind takes to get working (median so far): where its start-up stops land."""
        return statistics.median(self.ready_times) if self.ready_times else FIRST_STARTUP_GUESS


def child_starter(label: str) -> Callable[[RosSandbox], RosProcess]:
    """A starter running this script as the child `label`: one of the main() variants in CHILDREN."""
    def start(sandbox: RosSandbox) -> RosProcess:
        return sandbox.command([sys.executable, __file__, '--child', label], label=label)
    return start


def installed_starter(package: str, executable: str) -> Callable[[RosSandbox], RosProcess]:
    """A starter running the package's installed executable in the sandbox, whatever main() it has."""
    def start(sandbox: RosSandbox) -> RosProcess:
        return sandbox.run(package, executable)
    return start


def classify(kind: Kind, process: RosProcess) -> str:
    """The outcome of a stop, once the process that was sent SIGINT has ended (killed after KILL_AFTER).

    The outcomes are those of the module docstring; the first output of each that is not clean is
    printed.
    """
    sent = time.monotonic()
    while process.running() and time.monotonic() - sent < KILL_AFTER:
        time.sleep(POLL)
    if process.running():
        stacks = native_stacks(process.pid) if 'alive' not in kind.shown else ''
        process.send_signal(signal.SIGKILL)
        process.wait(10)
        return show(kind, 'alive', process, f'{process.output}\n{stacks}')
    kind.stop_times.append(time.monotonic() - sent)
    code = process.wait(10)
    output = process.output
    if code == 1 and 'Timeout (' in output:
        return show(kind, 'watchdog', process, output)
    if code != 0 and (('KeyboardInterrupt' in output and not MAIN_FRAME.search(output))
                      or (code == -signal.SIGINT and not output.strip())):
        # Python's own KeyboardInterrupt during the imports, or SIGINT before Python installed its
        # handler: every Python program does that.
        return show(kind, BEFORE_MAIN, process, output)
    if code != 0:
        name = signal.Signals(-code).name if code < 0 else f'exit {code}'
        return show(kind, name, process, output)
    if any(word in output for word in BAD_WORDS):
        return show(kind, 'traceback', process, output)
    if kind.servo and 'torque enabled: pan' in output and 'torque disabled: pan' not in output:
        return show(kind, 'torque left on', process, output)
    return 'clean'


def show(kind: Kind, what: str, process: RosProcess, text: str) -> str:
    """Return what; the first time the kind has that outcome, print text's first and last lines too."""
    if what not in kind.shown:
        kind.shown.add(what)
        lines = text.splitlines()
        if len(lines) > 2 * SHOWN_LINES:
            lines = [*lines[:SHOWN_LINES], '...', *lines[-SHOWN_LINES:]]
        print(f'--- {kind.label}: first {what} (pid {process.pid}), first and last lines:', *lines, '---',
              sep='\n', flush=True)
    return what


def stop_once(kind: Kind, sandbox: RosSandbox, startup: bool, start_timeout: float) -> None:
    """Start the kind once, SIGINT it in its start-up or steady phase, and count the outcome.

    A steady stop whose node does not get working within start_timeout counts as a start failure.
    """
    started = time.monotonic()
    process = kind.start(sandbox)
    if startup:
        time.sleep(random.uniform(0.0, kind.startup_window()))
        was_ready = any(re.search(kind.ready, line) for line in list(process.lines))
        phase = 'start-up'
    else:
        try:
            process.wait_for(kind.ready, timeout=start_timeout)
        except AssertionError as error:
            kind.counts['steady']['start failure'] += 1
            show(kind, 'start failure', process, str(error))
            process.stop(3.0)
            return
        kind.ready_times.append(time.monotonic() - started)
        time.sleep(random.uniform(*STEADY_DELAY))
        was_ready = True
        phase = 'steady'
    process.send_signal(signal.SIGINT)
    outcome = classify(kind, process)
    kind.counts[phase][outcome] += 1
    if startup:
        kind.counts[phase]['(signal after ready)' if was_ready else '(signal before ready)'] += 1


def start_simulators(sandbox: RosSandbox) -> list[RosProcess]:
    """Start imu_sim and the pan servo_sim in the sandbox: what the nodes under test talk to."""
    return [sandbox.run('olive_sim', 'imu_sim'),
            sandbox.run('olive_sim', 'servo_sim', '--ros-args', *SERVO_PARAMETERS, label='servo_sim pan')]


def check_simulators(sandbox: RosSandbox, simulators: list[RosProcess]) -> list[RosProcess]:
    """The simulators, restarted if one of them ended (which the run reports with its output)."""
    if all(simulator.running() for simulator in simulators):
        return simulators
    for simulator in simulators:
        if not simulator.running():
            print(f'--- {simulator.label} ended with exit code {simulator.wait(10)}; its output:',
                  simulator.tail(SHOWN_LINES), '---', sep='\n', flush=True)
        simulator.stop(3.0)
    return start_simulators(sandbox)


def not_clean(kind: Kind) -> int:
    """How many of the kind's stops so far were not clean, not counting interruptions before main()."""
    return sum(n for counts in kind.counts.values() for name, n in counts.items()
               if name not in NOT_COUNTED and not name.startswith('('))


def report(kind: Kind) -> None:
    """Print the kind's outcomes per phase, with a 95 % upper bound of the not-clean rate, and stop times."""
    for phase, counts in kind.counts.items():
        total = sum(n for name, n in counts.items() if not name.startswith('(') and name != BEFORE_MAIN)
        if not total:
            continue
        bad = total - counts['clean']
        detail = ', '.join(f'{n} {name}' for name, n in sorted(counts.items()))
        print(f'{kind.label} [{phase}]: {total} stops in main(), {bad} not clean ({100 * bad / total:.1f} %, '
              f'95 % upper bound {100 * upper_bound(bad, total):.1f} %): {detail}')
    if kind.stop_times:
        ordered = sorted(kind.stop_times)
        print(f'{kind.label}: SIGINT to exit p50 {ordered[len(ordered) // 2]:.2f} s, '
              f'max {ordered[-1]:.2f} s; start to working p50 {kind.startup_window():.2f} s')


def main() -> int:
    """Stop each chosen kind --stops times per phase, kinds interleaved, and print their reports."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--stops', type=int, default=50,
                        help='steady stops per kind (and as many start-up stops)')
    parser.add_argument('--hogs', type=int, default=2, help='busy-loop CPU hog processes during the run')
    parser.add_argument('--kinds', default=DEFAULT_KINDS,
                        help=f'comma-separated labels to run (default {DEFAULT_KINDS!r}), of: ' + ', '.join(
                            [*CHILDREN, 'imu_turtle', 'control_servo']))
    parser.add_argument('--no-startup', action='store_true', help='only steady stops')
    parser.add_argument('--flood', action='store_true',
                        help="also flood imu_turtle's IMU topic with messages, as fast as one process can")
    parser.add_argument('--start-timeout', type=float, default=30.0)
    args = parser.parse_args()

    kinds = [Kind(label, child_starter(label), CHILD_READY, servo='servo' in label)
             for label in CHILDREN if label != 'flood']
    kinds += [Kind('imu_turtle', installed_starter('olive_imu', 'imu_turtle'), IMU_READY, servo=False),
              Kind('control_servo', installed_starter('olive_servo', 'control_servo'), SERVO_READY,
                   servo=True)]
    wanted = [label.strip() for label in args.kinds.split(',')]
    unknown = set(wanted) - {kind.label for kind in kinds}
    if unknown:
        parser.error(f'unknown kinds: {", ".join(sorted(unknown))}')
    kinds = [kind for kind in kinds if kind.label in wanted]
    print(f'{args.stops} steady{"" if args.no_startup else " + start-up"} stops per kind, '
          f'{args.hogs} CPU hogs, '
          f'{os.cpu_count()} cores; rclpy {version("ros-rclpy")}, '
          f'Fast DDS {version("ros-fastdds", "ros-fastrtps")}', flush=True)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))  # stop the simulators and hogs on the way out
    started = time.monotonic()
    hogs = [RosProcess([sys.executable, '-c', HOG], dict(os.environ), label='cpu hog')
            for _ in range(args.hogs)]
    try:
        with RosSandbox() as sandbox:
            simulators = start_simulators(sandbox)
            if args.flood:
                sandbox.command([sys.executable, __file__, '--child', 'flood'], label='imu flood')
            every = max(1, args.stops // 10)
            for index in range(args.stops):
                for kind in kinds:
                    for startup in (False, True)[:1 if args.no_startup else 2]:
                        stop_once(kind, sandbox, startup, args.start_timeout)
                        simulators = check_simulators(sandbox, simulators)
                if (index + 1) % every == 0:
                    print(f'{index + 1}/{args.stops} after {time.monotonic() - started:.0f} s: '
                          + '; '.join(f'{kind.label} {not_clean(kind)} not clean' for kind in kinds),
                          flush=True)
    finally:
        for hog in hogs:
            hog.stop(1.0)
    print()
    for kind in kinds:
        report(kind)
    print(f'run time {time.monotonic() - started:.0f} s')
    return 0


if __name__ == '__main__':
    if sys.argv[1:2] == ['--child']:  # a node: its traceback must show only its own main()'s frames
        CHILDREN[sys.argv[2]]()
    else:
        sys.exit(main())
