"""System tests of turtlesim_node: a real process, real DDS, the test's own ROS domain."""

from __future__ import annotations

import math

import pytest
from geometry_msgs.msg import Twist
from ros_harness import wait_until
from std_srvs.srv import Empty
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

CENTER = 5.544444561004639
TURTLE_QOS = 7


def start_turtlesim(ros, *args: str):
    sim = ros.run('turtlesim', 'turtlesim_node', '--headless', *args)
    sim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    return sim


def latest(messages: list, timeout: float = 10.0, count: int = 1):
    wait_until(lambda: len(messages) >= count, timeout, f'{count} message(s)')
    return messages[-1]


def test_starts_headless_and_publishes_turtle1_pose_and_color(ros):
    sim = start_turtlesim(ros)
    sim.wait_for(r'\[turtlesim\]: Starting turtlesim with node name /turtlesim')
    poses = ros.probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    colors = ros.probe.collect(Color, '/turtle1/color_sensor', TURTLE_QOS)
    pose = latest(poses, count=3)
    assert (pose.x, pose.y, pose.theta) == (pytest.approx(CENTER), pytest.approx(CENTER), 0.0)
    assert (pose.linear_velocity, pose.angular_velocity) == (0.0, 0.0)
    color = latest(colors)
    assert (color.r, color.g, color.b) == (255, 255, 255)  # an untouched path layer reads white
    assert 'Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]' in sim.output
    assert sim.stop() == 0
    assert 'Traceback' not in sim.output


def test_cmd_vel_moves_turtle_and_services_answer(ros):
    start_turtlesim(ros)
    probe = ros.probe
    poses = probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    cmd = probe.node.create_publisher(Twist, '/turtle1/cmd_vel', TURTLE_QOS)
    latest(poses)
    wait_until(lambda: cmd.get_subscription_count() > 0, 10, 'cmd_vel subscriber')
    cmd.publish(Twist())  # warm-up: an all-zero command changes nothing
    twist = Twist()
    twist.linear.x = 2.0
    cmd.publish(twist)
    wait_until(lambda: poses[-1].x > CENTER + 0.5, 10, 'turtle1 moving east')
    assert poses[-1].linear_velocity == pytest.approx(2.0)
    assert probe.call(Spawn, '/spawn', Spawn.Request(x=1.0, y=1.0, name='')).name == 'turtle2'
    probe.call(TeleportAbsolute, '/turtle2/teleport_absolute',
               TeleportAbsolute.Request(x=2.0, y=3.0, theta=1.0))
    probe.call(TeleportRelative, '/turtle2/teleport_relative',
               TeleportRelative.Request(linear=0.0, angular=0.5))
    probe.call(SetPen, '/turtle2/set_pen', SetPen.Request(r=255, width=5))
    probe.call(Empty, '/clear', Empty.Request())
    probe.call(Kill, '/kill', Kill.Request(name='turtle2'))
    wait_until(lambda: not any(n == '/turtle2/pose' for n, _ in probe.node.get_topic_names_and_types()),
               10, 'turtle2 topics gone')
    theta = math.atan2(0, 1)
    assert theta == 0.0
