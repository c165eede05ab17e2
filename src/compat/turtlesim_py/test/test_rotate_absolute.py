"""RotateAbsolute semantics on a bare turtle (no ROS): the action server's per-tick logic."""

from __future__ import annotations

import pytest
from turtlesim_py import world
from turtlesim_py.canvas import Canvas
from turtlesim_py.turtle import RotationGoal

DT = world.TICK_DT


class RecordedGoal(RotationGoal):
    def __init__(self, theta: float) -> None:
        super().__init__(theta)
        self.feedback: list[float] = []
        self.outcome: tuple[str, float] | None = None
        self.cancel = False

    def cancel_requested(self) -> bool:
        return self.cancel

    def publish_feedback(self, remaining: float) -> None:
        self.feedback.append(remaining)

    def finish(self, status: str, delta: float) -> None:
        assert self.outcome is None, 'finished twice'
        self.outcome = (status, delta)


def tick_until_done(turtle, goal, canvas, limit=1000):
    for k in range(1, limit):
        result = turtle.update(DT, k * DT, canvas)
        if goal.outcome is not None:
            return k, result
    raise AssertionError('goal never finished')


def test_rotates_at_one_rad_per_s_with_feedback_each_tick_and_upstream_delta_sign(new_turtle):
    turtle, canvas = new_turtle(), Canvas()
    goal = RecordedGoal(1.57)
    turtle.start_rotation(goal)
    ticks, result = tick_until_done(turtle, goal, canvas)
    assert len(goal.feedback) == ticks  # one per tick, including the finishing one
    assert goal.feedback[0] == pytest.approx(1.57, abs=1e-6)
    assert all(a > b for a, b in zip(goal.feedback, goal.feedback[1:], strict=False))
    status, delta = goal.outcome
    assert status == 'succeeded'
    # 0.016 rad a tick: 1.552 after 97 ticks is within 0.02 of 1.57. delta = start - current,
    # negative for a positive turn, as in the ROS 2 actions tutorial.
    assert ticks == 98
    assert delta == pytest.approx(-97 * DT, abs=1e-6)
    assert abs(turtle.theta - 1.57) < 0.02
    assert result.pose.angular_velocity == 0.0
    assert turtle.logger.texts('INFO') == ['Rotation goal completed successfully']


@pytest.mark.parametrize(('start', 'target', 'sign'), [
    (0.0, -1.0, -1.0), (3.0, -3.0, 1.0), (-3.0, 3.0, -1.0), (0.0, 3.1416, -1.0)])
def test_takes_the_short_way(start, target, sign, new_turtle):
    turtle, canvas = new_turtle(theta=start), Canvas()
    goal = RecordedGoal(target)
    turtle.start_rotation(goal)
    pose = turtle.update(DT, DT, canvas).pose
    assert pose.angular_velocity == sign
    tick_until_done(turtle, goal, canvas)
    assert abs(world.normalize_angle(turtle.theta - target)) < 0.02


def test_within_tolerance_succeeds_at_once_and_stops(new_turtle):
    turtle, canvas = new_turtle(theta=0.5), Canvas()
    turtle.command_velocity(1.0, 0.0, 0.0, now=0.0)  # no goal yet: nothing aborted
    goal = RecordedGoal(0.515)
    turtle.start_rotation(goal)
    result = turtle.update(DT, DT, canvas)
    assert goal.outcome[0] == 'succeeded'
    assert (result.pose.linear_velocity, result.pose.angular_velocity) == (0.0, 0.0)


def test_new_goal_preempts_with_warning_and_abort(new_turtle):
    turtle, canvas = new_turtle(), Canvas()
    first = RecordedGoal(3.0)
    turtle.start_rotation(first)
    for k in range(1, 11):
        turtle.update(DT, k * DT, canvas)
    second = RecordedGoal(0.0)
    turtle.start_rotation(second)
    status, delta = first.outcome
    assert status == 'aborted'
    assert delta == pytest.approx(-9 * DT, abs=1e-6)  # the result computed so far (lags a tick)
    assert turtle.logger.texts('WARN') == [
        'Rotation goal received before a previous goal finished. Aborting previous goal']
    tick_until_done(turtle, second, canvas)
    assert second.outcome[0] == 'succeeded'


def test_cancel_stops_the_turtle(new_turtle):
    turtle, canvas = new_turtle(), Canvas()
    goal = RecordedGoal(2.0)
    turtle.start_rotation(goal)
    for k in range(1, 6):
        turtle.update(DT, k * DT, canvas)
    goal.cancel = True
    result = turtle.update(DT, 6 * DT, canvas)
    assert goal.outcome == ('canceled', pytest.approx(-4 * DT, abs=1e-6))
    assert result.pose.angular_velocity == 0.0
    assert 'Rotation goal canceled' in turtle.logger.texts('INFO')


def test_velocity_command_aborts_the_goal_then_applies(new_turtle):
    turtle, canvas = new_turtle(), Canvas()
    goal = RecordedGoal(2.0)
    turtle.start_rotation(goal)
    turtle.update(DT, DT, canvas)
    turtle.command_velocity(1.0, 0.0, 0.0, now=DT)
    assert goal.outcome[0] == 'aborted'
    assert turtle.logger.texts('WARN') == ['Velocity command received during rotation goal. Aborting goal']
    assert turtle.update(DT, 2 * DT, canvas).pose.linear_velocity == 1.0


def test_rotation_is_not_stopped_by_the_command_timeout(new_turtle):
    turtle, canvas = new_turtle(), Canvas()
    goal = RecordedGoal(-3.0)  # about 188 ticks, 3 s: longer than the 1 s timeout
    turtle.start_rotation(goal)
    ticks, _ = tick_until_done(turtle, goal, canvas)
    assert ticks > 1.0 / DT
    assert goal.outcome[0] == 'succeeded'
