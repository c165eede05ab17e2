"""The world model and one turtle's tick, checked against closed-form results (no ROS)."""

from __future__ import annotations

import math

import pytest
from turtlesim_py import world
from turtlesim_py.canvas import Canvas
from turtlesim_py.turtle import Turtle

DT = world.TICK_DT


def run(turtle: Turtle, ticks: int, canvas: Canvas | None = None, start: float = 0.0):
    canvas = canvas or Canvas()
    result = None
    for k in range(1, ticks + 1):
        result = turtle.update(DT, start + k * DT, canvas)
    return result


def test_world_constants_match_upstream():
    assert f'{world.WIDTH:f}' == '11.088889'
    assert f'{world.CENTER:f}' == '5.544445'
    assert world.TICK_DT == 0.016


@pytest.mark.parametrize(('angle', 'expected'), [
    (0.0, 0.0), (world.PI, -world.PI), (-world.PI, -world.PI), (3 * world.PI / 2, -world.PI / 2),
    (-7.0, -7.0 + 2 * world.PI), (100.0, 100.0 - 32 * world.PI)])
def test_normalize_angle_wraps_into_minus_pi_pi(angle, expected):
    assert world.normalize_angle(angle) == pytest.approx(expected, abs=1e-12)
    assert -world.PI <= world.normalize_angle(angle) < world.PI


def test_arc_lands_where_the_fixed_step_integration_says(new_turtle):
    # Held linear.x = 2, angular.z = 1 for N ticks: theta_k = k*a with a = dt, and each step
    # moves v*dt along theta_k (rotate first). Closed form of the sums:
    # sum cos(k a) = sin(N a/2) cos((N+1) a/2) / sin(a/2), same with sin for y.
    n, v, w = 50, 2.0, 1.0
    turtle = new_turtle()
    turtle.command_velocity(v, 0.0, w, now=0.0)
    pose = run(turtle, n).pose
    a = w * DT
    factor = math.sin(n * a / 2) / math.sin(a / 2)
    expected_x = world.CENTER + v * DT * factor * math.cos((n + 1) * a / 2)
    expected_y = world.CENTER + v * DT * factor * math.sin((n + 1) * a / 2)
    assert pose.x == pytest.approx(expected_x, abs=1e-4)
    assert pose.y == pytest.approx(expected_y, abs=1e-4)
    assert pose.theta == pytest.approx(n * a, abs=1e-9)
    assert (pose.linear_velocity, pose.angular_velocity) == (2.0, 1.0)


def test_reverse_reports_speed_as_a_magnitude_and_humble_applies_linear_y(new_turtle):
    turtle = new_turtle()
    turtle.command_velocity(-1.0, 0.5, -0.25, now=0.0)
    pose = run(turtle, 1).pose
    assert pose.linear_velocity == pytest.approx(math.hypot(1.0, 0.5))
    assert pose.angular_velocity == -0.25
    theta = -0.25 * DT
    assert pose.x == pytest.approx(world.CENTER + (-math.cos(theta) - 0.5 * math.sin(theta)) * DT)
    assert pose.y == pytest.approx(world.CENTER + (-math.sin(theta) + 0.5 * math.cos(theta)) * DT)


def test_command_times_out_after_one_second(new_turtle):
    turtle = new_turtle()
    turtle.command_velocity(1.0, 0.0, 0.0, now=0.0)
    canvas = Canvas()
    moving = [turtle.update(DT, k * DT, canvas).pose for k in range(1, 63)]  # up to 0.992 s
    assert all(p.linear_velocity == 1.0 for p in moving)
    stopped = [turtle.update(DT, k * DT, canvas).pose for k in range(63, 70)]  # 1.008 s on
    assert all(p.linear_velocity == 0.0 for p in stopped)
    assert stopped[-1].x == pytest.approx(world.CENTER + 62 * DT)


def test_wall_clamps_and_warns_with_the_internal_y(new_turtle):
    turtle = new_turtle(x=11.0, y=2.0)
    turtle.command_velocity(10.0, 0.0, 0.0, now=0.0)
    result = run(turtle, 3)
    assert result.pose.x == pytest.approx(world.WIDTH)
    warnings = turtle.logger.texts('WARN')
    assert len(warnings) == 3  # one per tick while it keeps pushing outwards
    y_down = world.HEIGHT - 2.0  # upstream prints the y-down value, not the world y
    assert warnings[0] == f'Oh no! I hit the wall! (Clamping from [x={11.0 + 0.16:f}, y={y_down:f}])'
    assert warnings[1] == f'Oh no! I hit the wall! (Clamping from [x={world.WIDTH + 0.16:f}, y={y_down:f}])'
    assert result.pose.linear_velocity == 10.0  # the wall does not zero the command


def test_teleport_absolute_caps_above_top_and_clamps_below_floor(new_turtle):
    turtle = new_turtle()
    turtle.teleport_absolute(3.0, 50.0, 1.0)
    pose = run(turtle, 1).pose
    assert (pose.x, pose.y, pose.theta) == (pytest.approx(3.0), pytest.approx(world.HEIGHT), 1.0)
    assert turtle.logger.texts('WARN') == []
    turtle.teleport_absolute(-1.0, -2.0, 4.0)
    pose = run(turtle, 1).pose
    assert (pose.x, pose.y) == (0.0, 0.0)
    assert pose.theta == pytest.approx(4.0 - 2 * world.PI)
    assert len(turtle.logger.texts('WARN')) == 1


def test_teleport_relative_turns_first_then_moves_and_keeps_velocity(new_turtle):
    turtle = new_turtle()
    turtle.command_velocity(0.0, 0.0, 0.0, now=0.0)
    turtle.teleport_relative(2.0, math.pi / 2)
    pose = run(turtle, 1).pose
    assert pose.x == pytest.approx(world.CENTER, abs=1e-6)
    assert pose.y == pytest.approx(world.CENTER + 2.0, abs=1e-6)
    assert pose.theta == pytest.approx(math.pi / 2)


def test_pen_draws_the_trail_and_teleport_honours_pen_off(new_turtle):
    canvas = Canvas()
    turtle = new_turtle(x=2.0, y=2.0)
    turtle.teleport_absolute(4.0, 2.0, 0.0)
    run(turtle, 1, canvas)
    row = round((world.HEIGHT - 2.0) * world.METER_PX)
    assert canvas.sample((135, row)) == (0xB3, 0xB8, 0xFF)
    turtle.set_pen(10, 20, 30, 0, 1)  # off: nothing else changes
    assert turtle.pen.color == (0xB3, 0xB8, 0xFF)
    assert turtle.pen.width == 3
    turtle.teleport_absolute(4.0, 5.0, 0.0)
    run(turtle, 1, canvas)
    assert canvas.sample((180, row - 60)) == (255, 255, 255)
    turtle.set_pen(10, 20, 30, 0, 0)  # width 0: Qt's default 1 px
    assert (turtle.pen.color, turtle.pen.width, turtle.pen.on) == ((10, 20, 30), 1, True)


def test_color_sensor_samples_before_this_ticks_trail(new_turtle):
    canvas = Canvas()
    turtle = new_turtle(x=1.0, y=1.0)
    turtle.command_velocity(1.0, 0.0, 0.0, now=0.0)
    first = turtle.update(DT, DT, canvas)
    assert first.color == (255, 255, 255)
    turtle.set_pen(200, 0, 0, 9, 0)
    turtle.command_velocity(0.0, 0.0, 1.0, now=DT)
    turtle.teleport_relative(0.0, 0.0)
    turtle.update(DT, 2 * DT, canvas)  # a teleport onto itself paints a dot where it stands
    assert turtle.update(DT, 3 * DT, canvas).color == (200, 0, 0)


def test_a_late_tick_is_made_up_at_its_own_time_unless_too_late():
    assert world.tick_time(10.0, 10.0165) == pytest.approx(10.016)  # on time: one step of 16 ms
    assert world.tick_time(10.0, 10.15) == pytest.approx(10.016)  # held back: made up at its time
    assert world.tick_time(10.0, 10.6) == 10.6  # further behind than the catch-up: now
    assert world.tick_time(10.0, 10.01) == 10.01  # early, or sim time's clock: the clock's time
    assert world.tick_time(10.0, 10.0) == 10.0  # sim time paused: the turtles wait
