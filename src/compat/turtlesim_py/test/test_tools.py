"""Node-free logic of turtle_teleop_key, draw_square and mimic."""

from __future__ import annotations

import math

import pytest
from turtlesim.msg import Pose
from turtlesim_py import draw_square, world
from turtlesim_py.canvas import Canvas
from turtlesim_py.mimic import twist_for
from turtlesim_py.turtle_teleop_key import Cancel, Drive, Quit, Rotate, action_for


@pytest.mark.parametrize(('key', 'expected'), [
    ('A', Drive(1.0, 0.0)), ('B', Drive(-1.0, 0.0)), ('C', Drive(0.0, -1.0)), ('D', Drive(0.0, 1.0)),
    ('g', Rotate(0.0)), ('t', Rotate(0.7854)), ('r', Rotate(1.5708)), ('e', Rotate(2.3562)),
    ('d', Rotate(3.1416)), ('c', Rotate(-2.3562)), ('v', Rotate(-1.5708)), ('b', Rotate(-0.7854)),
    ('x', None), ('G', None), ('[', None), ('\x1b', None)])
def test_teleop_keys(key, expected):
    assert action_for(ord(key)) == expected


def test_teleop_cancel_and_quit_are_lowercase_only():
    assert isinstance(action_for(ord('f')), Cancel)
    assert isinstance(action_for(ord('q')), Quit)
    assert action_for(ord('F')) is None
    assert action_for(ord('Q')) is None


def test_mimic_copies_speed_magnitude_and_turn_rate():
    twist = twist_for(Pose(linear_velocity=1.5, angular_velocity=-0.5))
    assert (twist.linear.x, twist.linear.y, twist.angular.z) == (1.5, 0.0, -0.5)


def test_draw_square_closes_a_two_metre_square_on_the_simulated_turtle(new_turtle):
    """draw_square's state machine in closed loop with the turtle's own tick."""
    turtle, canvas = new_turtle(), Canvas()
    pose = turtle.update(world.TICK_DT, world.TICK_DT, canvas).pose
    state, goal = draw_square.State.FORWARD, draw_square.goal_ahead(pose)
    corners = []
    for k in range(2, 4000):
        msg = Pose(x=pose.x, y=pose.y, theta=pose.theta, linear_velocity=pose.linear_velocity,
                   angular_velocity=pose.angular_velocity)
        state, goal, (linear, angular), reached = draw_square.step(state, msg, goal)
        if reached and state is draw_square.State.TURN:
            corners.append((pose.x, pose.y))
        turtle.command_velocity(linear, 0.0, angular, now=k * world.TICK_DT)
        pose = turtle.update(world.TICK_DT, k * world.TICK_DT, canvas).pose
        if len(corners) == 5:
            break
    c = world.CENTER
    expected = [(c + 2, c), (c + 2, c + 2), (c, c + 2), (c, c), (c + 2, c)]
    assert len(corners) == 5
    for (x, y), (ex, ey) in zip(corners, expected, strict=True):
        assert math.hypot(x - ex, y - ey) < 0.15
