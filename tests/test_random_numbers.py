"""random_number_ps over real DDS: publisher range and parameters, subscriber, exercises."""

import re
import signal
import time

from geometry_msgs.msg import Twist
from ros_harness import wait_until
from std_msgs.msg import Int32

PUBLISHED = r'\[random_number_publisher\]: Publishing: (-?\d+)'


def test_publisher_stays_in_its_range_and_subscriber_logs_every_number(ros):
    publisher = ros.run('random_number_ps', 'random_number_publisher',
                        '--ros-args', '-p', 'lower_limit:=5', '-p', 'upper_limit:=8')
    subscriber = ros.run('random_number_ps', 'random_number_subscriber')
    received = ros.probe.collect(Int32, 'random_numbers')
    wait_until(lambda: len(received) >= 3, 10, 'three numbers')
    assert all(5 <= msg.data <= 8 for msg in received)
    published = [int(m.group(1)) for m in publisher.wait_for(PUBLISHED, count=3)]
    assert all(5 <= n <= 8 for n in published)
    # The subscriber logs what was published, in order.
    logged = subscriber.wait_for(r'\[random_number_subscriber\]: Received: (-?\d+)', count=2)
    logged = [int(m.group(1)) for m in logged]
    all_published = [int(m.group(1)) for m in re.finditer(PUBLISHED, publisher.output)]
    assert any(all_published[i:i + 2] == logged for i in range(len(all_published))), (
        logged, all_published)


def test_default_range_is_1_to_100(ros):
    ros.run('random_number_ps', 'random_number_publisher')
    assert ros.probe.get_parameters('/random_number_publisher', 'lower_limit', 'upper_limit') == [1, 100]


def test_runtime_parameter_change_takes_effect(ros):
    ros.run('random_number_ps', 'random_number_publisher')
    results = ros.probe.set_parameters('/random_number_publisher', lower_limit=1000, upper_limit=1000)
    # Set one by one: upper first would be fine, lower first (1000 > 100) must be refused.
    assert [r.successful for r in results] == [False, True]
    results = ros.probe.set_parameters('/random_number_publisher', lower_limit=1000)
    assert results[0].successful, results[0].reason
    received = ros.probe.collect(Int32, 'random_numbers')
    wait_until(lambda: len(received) >= 2, 10, 'two numbers after the change')
    assert {msg.data for msg in received} == {1000}


def test_lower_above_upper_is_refused_with_a_reason(ros):
    ros.run('random_number_ps', 'random_number_publisher')
    [result] = ros.probe.set_parameters('/random_number_publisher', lower_limit=500)
    assert not result.successful
    assert 'lower_limit (500)' in result.reason
    assert 'upper_limit (100)' in result.reason
    [result] = ros.probe.set_parameters('/random_number_publisher', upper_limit=0)
    assert not result.successful
    assert ros.probe.get_parameters('/random_number_publisher', 'lower_limit', 'upper_limit') == [1, 100]


def test_wrong_parameter_type_is_refused_and_value_kept(ros):
    ros.run('random_number_ps', 'random_number_publisher')
    [result] = ros.probe.set_parameters('/random_number_publisher', upper_limit='lots')
    assert not result.successful
    assert result.reason
    [result] = ros.probe.set_parameters('/random_number_publisher', lower_limit=2.5)
    assert not result.successful
    assert ros.probe.get_parameters('/random_number_publisher', 'lower_limit', 'upper_limit') == [1, 100]


def test_bad_startup_limits_end_with_one_line_and_code_2(ros):
    publisher = ros.run('random_number_ps', 'random_number_publisher',
                        '--ros-args', '-p', 'lower_limit:=10', '-p', 'upper_limit:=3')
    assert publisher.wait(10) == 2
    assert 'Traceback' not in publisher.output
    assert 'lower_limit (10) must not be greater than upper_limit (3)' in publisher.output


def test_wrong_startup_parameter_type_ends_with_one_line_and_code_2(ros):
    publisher = ros.run('random_number_ps', 'random_number_publisher',
                        '--ros-args', '-p', 'upper_limit:=many')
    assert publisher.wait(10) == 2
    assert 'Traceback' not in publisher.output
    assert 'upper_limit' in publisher.output


def test_counter_publisher_counts_up_from_one(ros):
    counter = ros.run('random_number_ps', 'counter_publisher')
    counter.wait_for(r'Publishing: 1$')
    received = ros.probe.collect(Int32, 'random_numbers')
    wait_until(lambda: len(received) >= 2, 10, 'two counts')
    first = received[0].data
    assert first >= 1
    assert [m.data for m in received[:2]] == [first, first + 1]


def test_turtle_random_velocity_drives_the_configured_topic_within_limits(ros):
    ros.run('random_number_ps', 'turtle_random_velocity', '--ros-args',
            '-p', 'cmd_vel_topic:=/turtle2/cmd_vel', '-p', 'max_linear:=0.5',
            '-p', 'max_angular:=0.25', '-p', 'period:=0.1')
    received = ros.probe.collect(Twist, '/turtle2/cmd_vel')
    wait_until(lambda: len(received) >= 5, 10, 'five velocity commands')
    assert all(0.0 <= t.linear.x <= 0.5 and abs(t.angular.z) <= 0.25 for t in received)
    assert len({t.linear.x for t in received}) > 1


def test_turtle_random_velocity_refuses_out_of_range_limit(ros):
    ros.run('random_number_ps', 'turtle_random_velocity')
    [result] = ros.probe.set_parameters('/turtle_random_velocity', max_linear=-1.0)
    assert not result.successful
    [result] = ros.probe.set_parameters('/turtle_random_velocity', cmd_vel_topic='/elsewhere')
    assert not result.successful
    assert ros.probe.get_parameters('/turtle_random_velocity', 'max_linear', 'cmd_vel_topic') == [
        2.0, '/turtle1/cmd_vel']


def test_every_node_stops_cleanly_on_ctrl_c(ros):
    nodes = [ros.run('random_number_ps', exe) for exe in (
        'random_number_publisher', 'random_number_subscriber', 'counter_publisher',
        'turtle_random_velocity')]
    for name in ('random_number_publisher', 'random_number_subscriber', 'counter_publisher',
                 'turtle_random_velocity'):
        ros.probe.wait_until_spinning(name)
    for node in nodes:
        node.stop_cleanly()
        assert 'Traceback' not in node.output


def test_a_second_ctrl_c_during_shutdown_is_still_clean(ros):
    # A launcher forwarding SIGINT on top of the terminal's own gives a node two in a row.
    subscriber = ros.run('random_number_ps', 'random_number_subscriber')
    ros.probe.wait_until_spinning('random_number_subscriber')
    subscriber.send_signal(signal.SIGINT)
    time.sleep(0.05)  # the second one lands while the node is cleaning up
    subscriber.send_signal(signal.SIGINT)
    assert subscriber.wait(10) == 0, subscriber.output
    assert 'Traceback' not in subscriber.output
