"""The first `ros2` answer is complete: nodes that have been up for a second are all listed.

A student types `ros2 node list` a few seconds after `ros2 launch olive_launch turtle_launch.py`
(section 3.9: two turtlesim nodes). Whether the domain's `ros2` daemon is stopped (the call makes
its own node and starts the daemon for next time), was started a moment ago by `ros2 daemon start`,
or `--no-daemon` is given, the very first listing names both turtles, every time.
"""

import pytest
from owl_common.processes import stop_ros2_daemon
from ros_harness import RosHarness

TRIES = 6
TURTLES = ('/turtle1', '/turtle2')


@pytest.fixture(scope='module')
def turtles():
    """The launched turtles, in a domain that every way of asking below shares: they only read it."""
    harness = RosHarness()
    try:
        harness.command(['ros2', 'launch', 'olive_launch', 'turtle_launch.py'], label='turtle_launch')
        for name in ('turtle1', 'turtle2'):
            harness.probe.wait_until_spinning(name, timeout=30)
        yield harness
    finally:
        harness.close()


@pytest.mark.parametrize('how', ['daemon stopped', 'daemon just started', 'no daemon'])
def test_the_first_node_list_names_both_turtles(turtles: RosHarness, how: str):
    ros = turtles
    partial = []
    for _ in range(TRIES):
        stop_ros2_daemon(ros.domain_id)
        if how == 'daemon just started':
            assert ros.command(['ros2', 'daemon', 'start'], label='daemon start').wait(30) == 0
        listing = ros.command(['ros2', 'node', 'list', *(['--no-daemon'] if how == 'no daemon' else [])],
                              label='node list')
        assert listing.wait(30) == 0, listing.output
        if not set(TURTLES) <= set(listing.lines):
            partial.append(listing.output)
    assert not partial, f'{len(partial)} of {TRIES} first listings missed a turtle; the first:\n{partial[0]}'
