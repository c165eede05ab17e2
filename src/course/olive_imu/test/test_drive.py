"""Which way the turtle goes for which IMU tilt, and a minute of the scripted IMU's motion."""

import math

import pytest
from geometry_msgs.msg import Quaternion
from olive_imu.drive import turtle_velocity
from olive_imu.euler import quaternion_to_euler
from olive_imu.imu_turtle import PUBLISH_PERIOD
from olive_sim.imu_model import ScriptedMotion

# turtlesim's window: 11.09 m square, the turtle starting in the middle.
WINDOW = 11.088889
START = WINDOW / 2
# imu_turtle's defaults
SPEED_FACTOR = TURN_FACTOR = 1.5


def test_tilted_forward_drives_forward_and_turned_left_turns_left():
    assert turtle_velocity(0.3, 0.0, 1.5, 1.5) == pytest.approx((0.45, 0.0))
    assert turtle_velocity(-0.3, 0.0, 1.5, 1.5)[0] < 0
    assert turtle_velocity(0.0, 0.5, 1.5, 2.0) == pytest.approx((0.0, 1.0))
    assert turtle_velocity(0.0, -0.5, 1.5, 2.0)[1] < 0


def test_level_and_facing_ahead_stands_still():
    _roll, pitch, yaw = quaternion_to_euler(Quaternion())
    assert turtle_velocity(pitch, yaw, SPEED_FACTOR, TURN_FACTOR) == (0.0, 0.0)


@pytest.mark.parametrize('start', [0.0, 4.0, 19.0, 34.0, 51.0])
def test_the_simulated_imu_drives_the_turtle_around_inside_the_window(start):
    """Item 4 of issue 11: the scripted IMU drives the turtle around, never reaching a wall.

    olive_sim's scripted IMU, started any time before imu_turtle, drives the turtle around for a
    minute without reaching a wall.
    """
    motion, step = ScriptedMotion(), 0.016
    x = y = START
    theta = 0.0
    xs, ys, travelled = [], [], 0.0
    for k in range(round(60.0 / step)):
        t = start + k * step
        sample = start + math.floor((t - start) / PUBLISH_PERIOD) * PUBLISH_PERIOD  # held between publishes
        qx, qy, qz, qw = motion.orientation(sample)
        _, pitch, yaw = quaternion_to_euler(Quaternion(x=qx, y=qy, z=qz, w=qw))
        linear, angular = turtle_velocity(pitch, yaw, SPEED_FACTOR, TURN_FACTOR)
        theta += angular * step  # turtlesim's 16 ms step: turn, then move along the new heading
        x += linear * math.cos(theta) * step
        y += linear * math.sin(theta) * step
        xs.append(x)
        ys.append(y)
        travelled += abs(linear) * step
    assert travelled > 20.0
    assert max(xs) - min(xs) > 2.0  # around, not back and forth
    assert max(ys) - min(ys) > 2.0
    assert 0.5 < min(xs)
    assert max(xs) < WINDOW - 0.5
    assert 0.5 < min(ys)
    assert max(ys) < WINDOW - 0.5
