"""turtle1/rotate_absolute over real DDS: feedback, result, preemption, cancel, abort on cmd_vel."""

from __future__ import annotations

import math

import pytest
from action_msgs.msg import GoalStatus
from geometry_msgs.msg import Twist
from rclpy.action import ActionClient
from ros_harness import wait_until
from turtlesim.action import RotateAbsolute
from turtlesim.msg import Pose
from turtlesim.srv import Kill

TICK = 0.016


def start(ros):
    sim = ros.run('turtlesim', 'turtlesim_node', '--headless')
    sim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    client = ActionClient(ros.probe.node, RotateAbsolute, '/turtle1/rotate_absolute')
    assert client.wait_for_server(timeout_sec=15)
    return sim, client


def send(client, theta: float, feedback: list | None = None):
    callback = None if feedback is None else (lambda msg: feedback.append(msg.feedback.remaining))
    future = client.send_goal_async(RotateAbsolute.Goal(theta=theta), feedback_callback=callback)
    wait_until(future.done, 10, 'goal response')
    handle = future.result()
    assert handle.accepted
    return handle


def result_of(handle, timeout: float = 15.0):
    future = handle.get_result_async()
    wait_until(future.done, timeout, 'goal result')
    return future.result()


def test_goal_succeeds_with_feedback_and_upstream_delta_then_preempt_cancel_abort(ros):
    sim, client = start(ros)
    poses = ros.probe.collect(Pose, '/turtle1/pose', 7)

    feedback: list[float] = []
    done = result_of(send(client, 1.57, feedback))
    assert done.status == GoalStatus.STATUS_SUCCEEDED
    assert done.result.delta == pytest.approx(-97 * TICK, abs=1e-4)
    # The result and the feedback come on channels of their own: the last feedback may follow the result.
    wait_until(lambda: feedback and feedback[-1] == pytest.approx(1.57 - 97 * TICK, abs=1e-4), 5,
               'the last feedback, 0.018 rad remaining')
    assert len(feedback) > 50  # one per tick, 98 in all (a loaded reader may drop a few)
    sim.wait_for(r'\[turtlesim\]: Rotation goal completed successfully')
    wait_until(lambda: poses and abs(poses[-1].theta - 97 * TICK) < 1e-4, 5, 'pose at 1.552 rad')

    # A new goal while one runs: the old one is aborted with a warning (the course's D then G).
    first = send(client, -3.0)
    second = send(client, 1.57)
    assert result_of(first).status == GoalStatus.STATUS_ABORTED
    sim.wait_for(r'\[WARN\].*Rotation goal received before a previous goal finished. Aborting previous goal')
    assert result_of(second).status == GoalStatus.STATUS_SUCCEEDED

    # Cancel (teleop's f).
    running = send(client, -1.0)
    cancel = running.cancel_goal_async()
    wait_until(cancel.done, 10, 'cancel response')
    assert len(cancel.result().goals_canceling) == 1
    assert result_of(running).status == GoalStatus.STATUS_CANCELED
    sim.wait_for(r'\[INFO\].*Rotation goal canceled')

    # Any cmd_vel aborts the running goal.
    cmd = ros.probe.node.create_publisher(Twist, '/turtle1/cmd_vel', 7)
    wait_until(lambda: cmd.get_subscription_count() > 0, 10, 'cmd_vel subscriber')
    running = send(client, 3.0)
    cmd.publish(Twist())
    assert result_of(running).status == GoalStatus.STATUS_ABORTED
    sim.wait_for(r'\[WARN\].*Velocity command received during rotation goal. Aborting goal')

    # A heading that can never be reached is refused instead of turning forever.
    for theta in (math.nan, math.inf):
        future = client.send_goal_async(RotateAbsolute.Goal(theta=theta))
        wait_until(future.done, 10, 'goal response')
        assert not future.result().accepted
    sim.wait_for(r'\[ERROR\].*Refusing rotation goal for turtle \[turtle1\]: '
                 r'every value must be finite \(theta=nan\)')
    assert sim.running()
    assert 'Traceback' not in sim.output


def test_killing_a_rotating_turtle_ends_its_goal_without_harm(ros):
    sim, client = start(ros)
    running = send(client, 3.0)
    ros.probe.call(Kill, '/kill', Kill.Request(name='turtle1'))
    # The goal ends aborted, or its server is gone before the result got out: never a crash.
    future = running.get_result_async()
    wait_until(lambda: future.done() or not client.server_is_ready(), 10, 'goal end or server gone')
    if future.done():
        assert future.result().status == GoalStatus.STATUS_ABORTED
    assert sim.running()
    assert 'Traceback' not in sim.output
    sim.stop_cleanly()
