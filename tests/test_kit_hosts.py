"""The kit split across network hosts (`ros2 run olive_sim kit_hosts`) and `owl network`.

kit_hosts puts each module in a network namespace at the course's address on one bridge and joins
"this machine" to it. Here "this machine" is itself a namespace (the student's PC), so no DDS
traffic of the test leaves the namespaces it made. From the PC, over real DDS: imu_control_robot
drives the servos; a module whose cable is pulled past its lease is seen again within 5 s; and
`owl network` reports the good set-up and says what is wrong, with the fix, in broken ones.
"""

import os
import re
import subprocess
import time
from pathlib import Path

import pytest
from gates import prerequisite_missing
from netns import TestLan
from olive_sim.network_hosts import setup_problem
from owl_common.processes import RosProcess
from ros_harness import wait_until

OPEN = {'OWL_NETWORK': 'open', 'ROS_DOMAIN_ID': '0'}
RECONNECT_LIMIT = 5.0  # s: the bound for a module coming back
PULLED_FOR = 12.0      # s: longer than the participants' 10 s lease (config/fastdds.xml)


def positions(process) -> list[float]:
    """Joint positions a `ros2 topic echo ... --field position` process has printed so far.

    A float64[] field prints as Python's array, `array('d', [0.25])`, as upstream's echo does.
    """
    return [float(v) for v in re.findall(r"^array\('d', \[([-+0-9.e]+)\]\)$", process.output, re.M)]


class Classroom(TestLan):
    """The classroom fixture's Lan, with the PC's kit_hosts process."""

    kit: RosProcess


@pytest.fixture
def classroom():
    """A student's PC and, not on the kit's bridge, a second machine (both namespaces).

    The PC runs kit_hosts, which joins it to the kit's bridge at 10.42.0.1.
    """
    lan = Classroom()
    try:
        lan.add_host('pc', None)
        lan.add_host('other', None)
        kit = lan.run('pc', 'ros2 run olive_sim kit_hosts', {}, label='kit_hosts')
        kit.wait_for(r'in your shells', timeout=60)
        lan.kit = kit
        yield lan
    finally:
        lan.close()


def test_the_modules_are_hosts_at_the_course_addresses_and_imu_control_robot_drives_them(classroom):
    for address in ('10.42.0.20', '10.42.0.8', '10.42.0.9', '10.42.0.10'):
        assert address in classroom.kit.output
    pan = classroom.run('pc', 'ros2 topic echo /olive/servo/pan/joint --field position', OPEN)
    tilt = classroom.run('pc', 'ros2 topic echo /olive/servo/tilt/joint --field position', OPEN)
    started = time.monotonic()
    robot = classroom.run('pc', 'ros2 run olive_servo imu_control_robot', OPEN, label='imu_control_robot')
    robot.wait_for(r'steering the pan and tilt servos', timeout=60)
    print(f'imu_control_robot steered {time.monotonic() - started:.2f} s after it started')
    def swept(echo) -> bool:
        # each echo's first line comes when its own subscription is matched: pan's may be long before tilt's
        seen = positions(echo)
        return len(seen) > 50 and max(seen) - min(seen) > 0.3

    wait_until(lambda: swept(pan) and swept(tilt), 40, 'both servos to follow the IMU')
    robot.stop_cleanly()
    assert 'torque disabled' in robot.output


def descendants(pid: int) -> list[int]:
    """Every process below pid, from /proc."""
    children: dict[int, list[int]] = {}
    for stat in Path('/proc').glob('[0-9]*/stat'):
        try:
            fields = stat.read_text().rsplit(')', 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    found, todo = [], [pid]
    while todo:
        below = children.get(todo.pop(), [])
        found += below
        todo += below
    return found


def set_module_link(kit, module_argument: str, state: str) -> None:
    """Pull out (down) or plug in (up) a module host's cable.

    kit_hosts made its namespaces inside the PC's own mount namespace, so they are entered through the
    module process's /proc entry.
    """
    for pid in descendants(kit.pid):
        try:
            command = Path(f'/proc/{pid}/cmdline').read_bytes().split(b'\0')
        except OSError:
            continue
        if module_argument.encode() in command and any(b'servo_sim' in part for part in command):
            subprocess.run(['nsenter', f'--net=/proc/{pid}/ns/net', 'ip', 'link', 'set', 'eth0', state],
                           check=True, timeout=10)
            return
    raise AssertionError(f'no module process with {module_argument} under kit_hosts')


def test_a_module_whose_cable_is_pulled_is_seen_again_within_5_s(classroom):
    pan = classroom.run('pc', 'ros2 topic echo /olive/servo/pan/joint --field position', OPEN)
    wait_until(lambda: len(positions(pan)) > 20, 60, 'pan joint states on the PC')
    set_module_link(classroom.kit, 'namespace:=pan', 'down')
    time.sleep(0.5)
    before = len(positions(pan))
    time.sleep(PULLED_FOR)  # the PC forgets the module: coming back takes a new discovery
    assert len(positions(pan)) - before < 5, 'joint states still arrive with the cable pulled'
    plugged = time.monotonic()
    set_module_link(classroom.kit, 'namespace:=pan', 'up')
    count = len(positions(pan))
    wait_until(lambda: len(positions(pan)) > count + 5, RECONNECT_LIMIT, 'pan joint states again')
    print(f'pan joint states back {time.monotonic() - plugged:.2f} s after the cable was plugged in')
    assert classroom.kit.running()
    assert pan.running()
    assert 'Traceback' not in classroom.kit.output + pan.output


def owl_network(check) -> tuple[int, list[str]]:
    """The exit code and report lines of an `owl network` started by start_owl_network."""
    code = check.wait(60)
    return code, [line for line in check.lines if line.startswith('owl network: ')]


def start_owl_network(classroom, host: str, env: dict):
    return classroom.run(host, 'owl network --discovery-time 3', env, label=f'owl network on {host}')


def test_owl_network_on_a_good_set_up_and_three_broken_ones(classroom):
    # Each waits out its discovery time: the four run at once, in shells of their own.
    good, private, other_domain, off_the_bridge = (
        start_owl_network(classroom, host, env) for host, env in (
            ('pc', OPEN),
            ('pc', {'ROS_DOMAIN_ID': '0'}),  # OWL_NETWORK left at private
            ('pc', {**OPEN, 'ROS_DOMAIN_ID': '7'}),
            ('other', OPEN)))
    code, lines = owl_network(good)
    print('\n'.join(['good set-up:', *lines]))
    assert code == 0, lines
    assert all(': ok: ' in line for line in lines), lines
    assert any('discovers 4 Olive module node(s)' in line for line in lines), lines
    assert lines[-1].startswith('owl network: ok: Humble modules are safe beside this shell'), lines

    code, lines = owl_network(private)
    print('\n'.join(['private mode:', *lines]))
    assert code == 1
    assert 'fix: export OWL_NETWORK=open; source env.sh' in lines[0]

    code, lines = owl_network(other_domain)
    print('\n'.join(['another domain:', *lines]))
    assert code == 1, lines
    assert lines[-2].endswith('this shell is in domain 7; fix: export ROS_DOMAIN_ID=0'), lines

    code, lines = owl_network(off_the_bridge)
    print('\n'.join(['not on the bridge:', *lines]))
    assert code == 1, lines
    assert "no network interface on the modules' subnet 10.42.0.0/24" in lines[1], lines


# Runs "$@" in a mount namespace of its own whose /run/netns starts empty, then lists that folder: a
# network namespace the command made would be listed, and none that another test makes meanwhile
# (comparing the machine's `ip netns list` before and after failed whenever one did).
WITH_PRIVATE_NETNS_FOLDER = 'mkdir -p /run/netns && mount -t tmpfs owl-test /run/netns && "$@"; ' \
                            'code=$?; echo namespaces:; ls -A /run/netns; exit $code'


@pytest.mark.parametrize(('args', 'message'), [
    (['--student-address', '192.168.1.5'], '192.168.1.5 is not a host address of the subnet 10.42.0.0/24'),
    (['--student-address', '10.42.0.8'], '10.42.0.8 is already taken on 10.42.0.0/24'),
    (['--student-address', 'tenfortytwo'], "'tenfortytwo' is not an IPv4 address"),
])
def test_kit_hosts_refuses_a_wrong_address_in_one_line_and_makes_nothing(args, message):
    if problem := setup_problem():
        prerequisite_missing(f'{problem}, so this network test is skipped')
    result = subprocess.run(['unshare', '--mount', '--propagation', 'private', 'sh', '-c',
                             WITH_PRIVATE_NETNS_FOLDER, 'sh', 'ros2', 'run', 'olive_sim', 'kit_hosts', *args],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert result.stderr.strip() == f'kit_hosts: error: --student-address: {message}'
    assert result.stdout.endswith('namespaces:\n'), result.stdout  # none made


@pytest.mark.parametrize(('args', 'message'), [
    (['--timeout', 'soon'], "argument --timeout: 'soon' is not a number of seconds"),
    (['--discovery-time', '-1'], 'argument --discovery-time: -1 is not between 0 and 60 seconds'),
])
def test_owl_network_refuses_bad_arguments_in_one_line(args, message):
    result = subprocess.run(['owl', 'network', *args], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert 'Traceback' not in result.stderr
    assert result.stderr.strip().splitlines()[-1] == f'owl network: error: {message}'


def test_owl_network_refuses_a_domain_no_node_can_use_in_one_line():
    result = subprocess.run(['owl', 'network'], capture_output=True, text=True, timeout=60,
                            env={**os.environ, 'ROS_DOMAIN_ID': '233'})
    assert result.returncode == 1
    assert result.stderr == ''
    assert result.stdout == ("owl network: problem: ROS_DOMAIN_ID is '233'; it must be a number from 0 "
                             'to 232; fix: export ROS_DOMAIN_ID=0\n')


@pytest.mark.parametrize(('args', 'message'), [
    (['network', '--what'], 'owl: error: unrecognized arguments: --what'),
    (['netwerk'], "owl: error: argument COMMAND: invalid choice: 'netwerk' "
                  "(choose from 'check', 'class', 'demo', 'network', 'pages', 'windows')"),
    (['class', 'serv'], "owl class: error: argument COMMAND: invalid choice: 'serv' "
                        "(choose from 'serve', 'image')"),
])
def test_owl_refuses_unknown_words_in_one_line(args, message):
    result = subprocess.run(['owl', *args], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert 'Traceback' not in result.stderr
    assert result.stderr.strip().splitlines()[-1] == message
