"""Classroom networks over real DDS between network namespaces: two students' laptops on one LAN.

Both laptops are in the ROS 2 default domain 0 and see each other only when they open their network
mode (env.sh's OWL_NETWORK); a wrong mode changes nothing.
"""

import subprocess
import time

import pytest
from netns import ROOT, TestLan

PUBLISHER = 'ros2 run random_number_ps random_number_publisher'
LISTENER = 'ros2 topic echo /random_numbers std_msgs/msg/Int32'
QUIET_WINDOW = 8.0  # s a private laptop listens without hearing the other one: > 10x the open discovery time


@pytest.fixture
def classroom():
    lan = TestLan()
    try:
        lan.add_host('laptop_a', '10.42.0.101')
        lan.add_host('laptop_b', '10.42.0.102')
        yield lan
    finally:
        lan.close()


def publisher_and_listener(lan: TestLan, mode: str):
    """laptop_a publishes random numbers; laptop_b and laptop_a itself listen.

    Returns (when the publisher's process started, laptop_b's listener, laptop_a's own listener).
    """
    env = {'OWL_NETWORK': mode}
    listener_b = lan.run('laptop_b', LISTENER, env, label='laptop_b listener')
    listener_a = lan.run('laptop_a', LISTENER, env, label='laptop_a listener')
    listener_b.wait_for(r'network ', timeout=30)  # its env.sh ran; the listener is starting
    started = time.monotonic()
    publisher = lan.run('laptop_a', PUBLISHER, env, label='laptop_a publisher')
    publisher.wait_for(r'Publishing: ', timeout=30)
    return started, listener_b, listener_a


def test_two_laptops_in_the_default_private_mode_do_not_see_each_other(classroom):
    _, listener_b, listener_a = publisher_and_listener(classroom, 'private')
    listener_a.wait_for(r'data: ', timeout=20)  # private still works on the laptop itself
    # laptop_b's own look at the graph, inside the quiet window rather than after it
    nodes = classroom.run('laptop_b', 'ros2 node list --no-daemon --spin-time 2', {}, label='node list')
    time.sleep(QUIET_WINDOW)
    assert 'data:' not in listener_b.output, listener_b.output
    assert nodes.wait(30) == 0
    assert 'random_number_publisher' not in nodes.output, nodes.output
    assert 'network private' in nodes.output  # env.sh said which mode the shell is in


def test_with_the_network_open_the_laptops_see_each_other(classroom):
    started, listener_b, _ = publisher_and_listener(classroom, 'open')
    listener_b.wait_for(r'data: ', timeout=20)
    discovery = time.monotonic() - started
    print(f'laptop_b received its first number {discovery:.2f} s after the publisher on laptop_a started')
    nodes = classroom.run('laptop_b', 'ros2 node list --no-daemon --spin-time 2', {'OWL_NETWORK': 'open'},
                          label='node list')
    assert nodes.wait(30) == 0
    assert '/random_number_publisher' in nodes.output, nodes.output
    assert 'network open' in nodes.output


def test_a_wrong_network_mode_is_one_line_and_changes_nothing():
    script = ('export ROS_AUTOMATIC_DISCOVERY_RANGE=BEFORE; OWL_NETWORK=everyone source ./env.sh; '
              'echo "code=$? range=$ROS_AUTOMATIC_DISCOVERY_RANGE venv=${VIRTUAL_ENV:-none}"')
    result = subprocess.run(['bash', '-c', script], capture_output=True, text=True, cwd=ROOT, timeout=30,
                            env={'PATH': '/usr/bin:/bin', 'HOME': '/tmp'}, check=False)
    assert result.stdout.strip() == 'code=1 range=BEFORE venv=none', result.stdout + result.stderr
    assert result.stderr.strip() == ("env.sh: OWL_NETWORK must be 'private' or 'open', not 'everyone'; "
                                     'nothing in this shell was changed')
