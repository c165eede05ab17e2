"""System tests of turtlesim_node: a real process, real DDS, the test's own ROS domain."""

from __future__ import annotations

import io
import math

import pytest
from geometry_msgs.msg import Twist
from PIL import Image
from rcl_interfaces.srv import DescribeParameters
from rclpy.qos import DurabilityPolicy, ReliabilityPolicy
from ros_harness import wait_until
from sensor_msgs.msg import CompressedImage
from std_srvs.srv import Empty, Trigger
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

CENTER = 5.544444561004639
TURTLE_QOS = 7
BACKGROUND = (69, 86, 255)
PEN = (0xB3, 0xB8, 0xFF)


def start_turtlesim(ros, *args: str):
    sim = ros.run('turtlesim', 'turtlesim_node', '--headless', *args)
    sim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    return sim


def latest(messages: list, timeout: float = 10.0, count: int = 1):
    wait_until(lambda: len(messages) >= count, timeout, f'{count} message(s)')
    return messages[-1]


def spawn(ros, name: str = '', x: float = 1.0, y: float = 1.0, theta: float = 0.0) -> str:
    return ros.probe.call(Spawn, '/spawn', Spawn.Request(x=x, y=y, theta=theta, name=name)).name


def teleport(ros, turtle: str, x: float, y: float, theta: float = 0.0) -> None:
    ros.probe.call(TeleportAbsolute, f'/{turtle}/teleport_absolute',
                   TeleportAbsolute.Request(x=x, y=y, theta=theta))


def set_pen(ros, turtle: str, r: int = 0, g: int = 0, b: int = 0, width: int = 0, off: int = 0) -> None:
    ros.probe.call(SetPen, f'/{turtle}/set_pen', SetPen.Request(r=r, g=g, b=b, width=width, off=off))


def snapshot(ros, path) -> Image.Image:
    """The canvas as the hidden ~/_save_canvas service writes it."""
    response = ros.probe.call(Trigger, '/turtlesim/_save_canvas', Trigger.Request())
    assert response.success, response.message
    with Image.open(path) as image:
        return image.convert('RGB')


def pixel(x: float, y: float) -> tuple[int, int]:
    """Canvas pixel of a world position."""
    return round(x * 45), round((11.088889 - y) * 45)


def settled(poses: list, predicate, what: str) -> Pose:
    wait_until(lambda: poses and predicate(poses[-1]), 10, what)
    return poses[-1]


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
    # Over a trail it reads the pen: a teleport onto itself leaves a dot under the turtle.
    set_pen(ros, 'turtle1', r=200, g=10, b=20, width=10)
    ros.probe.call(TeleportRelative, '/turtle1/teleport_relative', TeleportRelative.Request())
    wait_until(lambda: (colors[-1].r, colors[-1].g, colors[-1].b) == (200, 10, 20), 10, 'pen colour sensed')
    assert 'Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]' in sim.output
    for topic in ('/turtle1/pose', '/turtle1/color_sensor'):
        (info,) = ros.probe.node.get_publishers_info_by_topic(topic)
        assert info.qos_profile.reliability == ReliabilityPolicy.RELIABLE
        assert info.qos_profile.durability == DurabilityPolicy.VOLATILE
    sim.stop_cleanly()
    assert 'Traceback' not in sim.output


def test_cmd_vel_drives_the_turtle_and_times_out(ros):
    sim = start_turtlesim(ros)
    poses = ros.probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    cmd = ros.probe.node.create_publisher(Twist, '/turtle1/cmd_vel', TURTLE_QOS)
    latest(poses)
    wait_until(lambda: cmd.get_subscription_count() > 0, 10, 'cmd_vel subscriber')
    twist = Twist()
    twist.linear.x, twist.angular.z = 2.0, 1.0
    cmd.publish(twist)
    moving = settled(poses, lambda p: p.linear_velocity == 2.0, 'turtle1 moving')
    assert moving.angular_velocity == 1.0
    # One message keeps it going for 1 s (62 or 63 ticks), then it stops: a 2 m arc.
    stopped = settled(poses, lambda p: p.linear_velocity == 0.0, 'turtle1 stopped by the timeout')
    assert stopped.angular_velocity == 0.0
    moving_ticks = sum(p.linear_velocity == 2.0 for p in poses)
    # theta is a float32: 64 ticks are 1.0240000486 rad
    assert 61 * 0.016 - 1e-6 <= stopped.theta <= 64 * 0.016 + 1e-6, (
        f'turned {stopped.theta:.3f} rad; the probe saw {moving_ticks} poses of the moving turtle')
    assert math.hypot(stopped.x - CENTER, stopped.y - CENTER) == pytest.approx(
        2 * 2.0 * math.sin(stopped.theta / 2), abs=0.04)  # chord of a radius-2 arc

    twist.linear.x, twist.angular.z = math.nan, 0.0
    cmd.publish(twist)  # refused with an error; the pose stays finite
    sim.wait_for(r'\[ERROR\].*Refusing velocity command for turtle \[turtle1\]: every value must be finite '
                 r'\(linear.x=nan, linear.y=0.0, angular.z=0.0\)')
    twist.linear.x, twist.angular.z = 10.0, 0.0
    cmd.publish(twist)
    settled(poses, lambda p: p.x == pytest.approx(11.088889), 'turtle1 at the east wall')
    assert all(math.isfinite(p.x) and math.isfinite(p.y) for p in poses)


def test_spawn_naming_kill_clear_reset(ros, tmp_path):
    png = tmp_path / 'canvas.png'
    sim = start_turtlesim(ros, '--canvas-png', str(png))
    assert spawn(ros) == 'turtle2'
    assert spawn(ros, 'turtle3') == 'turtle3'
    assert spawn(ros) == 'turtle4'  # turtle3 is taken
    sim.wait_for(r'Spawning turtle \[turtle4\] at x=\[1.000000\], y=\[1.000000\], theta=\[0.000000\]')
    assert spawn(ros, 'turtle2') == ''
    sim.wait_for(r'\[ERROR\].*A turtle named \[turtle2\] already exists')
    ros.probe.call(Kill, '/kill', Kill.Request(name='turtle1'))
    assert spawn(ros) == 'turtle5'  # names are not reused
    ros.probe.call(Kill, '/kill', Kill.Request(name='nobody'))
    sim.wait_for(r'\[ERROR\].*Tried to kill turtle \[nobody\], which does not exist')
    wait_until(lambda: '/turtle1/pose' not in dict(ros.probe.node.get_topic_names_and_types()),
               10, 'turtle1 topics gone')

    # A trail with the default pen, one with width 0 (1 px), one with the pen off. A teleport is done
    # (and its trail drawn) at turtlesim's next tick, as upstream: the next pen waits for its pose.
    poses: list[Pose] = []
    subscription = ros.probe.node.create_subscription(Pose, '/turtle2/pose', poses.append, TURTLE_QOS)
    for x, y, pen in ((5.0, 1.0, {'r': 255, 'width': 0}), (5.0, 5.0, {'off': 1}), (9.0, 5.0, None)):
        teleport(ros, 'turtle2', x, y)
        settled(poses, lambda p, x=x, y=y: (p.x, p.y) == (pytest.approx(x), pytest.approx(y)),
                f'turtle2 teleported to ({x}, {y})')
        if pen:
            set_pen(ros, 'turtle2', **pen)
    ros.probe.node.destroy_subscription(subscription)  # turtle2's topics are to leave the graph below
    wait_until(lambda: 'Traceback' not in sim.output, 1, 'no crash')
    image = snapshot(ros, png)
    assert image.getpixel(pixel(3.0, 1.0)) == PEN
    column, row = pixel(5.0, 3.0)
    assert image.getpixel((column, row)) == (255, 0, 0)
    assert image.getpixel((column + 2, row)) == BACKGROUND  # 1 px wide
    assert image.getpixel(pixel(7.0, 5.0)) == BACKGROUND  # pen off
    assert image.getpixel((2, 2)) == BACKGROUND

    ros.probe.call(Empty, '/clear', Empty.Request())
    sim.wait_for(r'\[INFO\].*Clearing turtlesim\.')
    image = snapshot(ros, png)
    assert image.getpixel(pixel(3.0, 1.0)) == BACKGROUND
    assert '/turtle2/pose' in dict(ros.probe.node.get_topic_names_and_types())  # turtles untouched

    teleport(ros, 'turtle2', 2.0, 1.0)
    ros.probe.set_parameters('turtlesim', background_g=0)
    ros.probe.call(Empty, '/reset', Empty.Request())
    sim.wait_for(r'\[INFO\].*Resetting turtlesim\.')
    sim.wait_for(r'Spawning turtle \[turtle1\] at x=\[5.544445\], y=\[5.544445\], theta=\[0.000000\]',
                 count=2)
    # the new turtle1's topics reach the probe by discovery, some time after the log line
    wait_until(lambda: '/turtle1/pose' in dict(ros.probe.node.get_topic_names_and_types()),
               10, 'the new turtle1 publishing its pose')
    wait_until(lambda: not any(t.startswith(('/turtle2/', '/turtle3/'))
                               for t in dict(ros.probe.node.get_topic_names_and_types())),
               10, 'all but turtle1 gone')
    image = snapshot(ros, png)
    assert image.getpixel(pixel(3.0, 1.0)) == (69, 0, 255)  # trails gone, background kept
    assert ros.probe.get_parameters('turtlesim', 'background_g') == [0]
    assert spawn(ros) == 'turtle2'  # the counter starts again
    assert sim.running()
    assert 'Traceback' not in sim.output


def test_bad_input_is_refused_and_logged_never_fatal(ros):
    sim = start_turtlesim(ros)
    poses = ros.probe.collect(Pose, '/turtle1/pose', TURTLE_QOS)
    for bad in ('bad name', '1turtle', 'a//b', 'turtle?'):
        assert spawn(ros, bad) == ''
        sim.wait_for(rf'\[ERROR\].*Cannot spawn a turtle named \[{bad.replace("?", "[?]")}\]')
    assert spawn(ros, 'fine', x=math.nan) == ''
    sim.wait_for(r'\[ERROR\].*Refusing to spawn \[fine\]: every value must be finite \(x=nan')
    teleport(ros, 'turtle1', math.nan, 1.0)
    ros.probe.call(TeleportRelative, '/turtle1/teleport_relative',
                   TeleportRelative.Request(linear=math.inf, angular=0.0))
    sim.wait_for(r'\[ERROR\].*Refusing teleport_absolute for turtle \[turtle1\]: every value must be finite '
                 r'\(x=nan, y=1.0, theta=0.0\)')
    sim.wait_for(r'\[ERROR\].*Refusing teleport_relative for turtle \[turtle1\]')
    latest(poses, count=5)
    assert (poses[-1].x, poses[-1].y) == (pytest.approx(CENTER), pytest.approx(CENTER))
    # Huge but finite teleports are clamped to the wall, as upstream does.
    teleport(ros, 'turtle1', 1e30, -1e30)
    settled(poses, lambda p: (p.x, p.y) == (pytest.approx(11.088889), 0.0), 'clamped to the corner')
    sim.wait_for(r'\[WARN\].*Oh no! I hit the wall! \(Clamping from \[x=')
    assert spawn(ros) == 'turtle2'  # still serving
    assert sim.running()
    assert 'Traceback' not in sim.output


def test_background_parameters(ros, tmp_path):
    png = tmp_path / 'canvas.png'
    sim = start_turtlesim(ros, '--canvas-png', str(png))
    assert ros.probe.get_parameters('turtlesim', 'background_r', 'background_g', 'background_b') == [
        69, 86, 255]
    described = ros.probe.call(DescribeParameters, '/turtlesim/describe_parameters',
                               DescribeParameters.Request(names=['background_r'])).descriptors[0]
    assert described.description == 'Red channel of the background color'
    (limits,) = described.integer_range
    assert (limits.from_value, limits.to_value, limits.step) == (0, 255, 1)

    assert snapshot(ros, png).getpixel((10, 10)) == BACKGROUND
    (ok,) = ros.probe.set_parameters('turtlesim', background_r=255)
    assert ok.successful
    wait_until(lambda: snapshot(ros, png).getpixel((10, 10)) == (255, 86, 255), 10, 'purple background')
    for wrong in ({'background_g': 256}, {'background_g': -1}, {'background_b': 'blue'},
                  {'background_b': 1.5}):
        (result,) = ros.probe.set_parameters('turtlesim', **wrong)
        assert not result.successful
    assert ros.probe.get_parameters('turtlesim', 'background_g', 'background_b') == [86, 255]

    # What `ros2 param dump /turtlesim` shows in the course, besides the background.
    qos = 'qos_overrides./parameter_events.publisher.'
    assert ros.probe.get_parameters('turtlesim', 'use_sim_time', *(qos + p for p in (
        'depth', 'durability', 'history', 'reliability'))) == [
        False, 1000, 'volatile', 'keep_last', 'reliable']
    (result,) = ros.probe.set_parameters('turtlesim', **{qos + 'depth': 5})
    assert not result.successful  # read-only
    assert sim.running()


@pytest.mark.parametrize('override', ['background_r:=300', 'background_b:=blue'])
def test_bad_startup_parameter_is_one_line_and_exit_2(ros, override):
    sim = ros.run('turtlesim', 'turtlesim_node', '--headless', '--ros-args', '-p', override)
    assert sim.wait(timeout=30) == 2
    assert sim.output.startswith('error: ')
    assert 'Traceback' not in sim.output


def test_canvas_image_topic_is_opt_in_and_save_errors_are_reported(ros, tmp_path):
    sim = start_turtlesim(ros, '--publish-image', '--canvas-png', str(tmp_path / 'missing' / 'c.png'))
    images = ros.probe.collect(CompressedImage, '/turtlesim/canvas/compressed', 1)
    ros.probe.set_parameters('turtlesim', background_b=0)
    wait_until(lambda: images and _decode(images[-1]).getpixel((10, 10)) == (69, 86, 0), 15,
               'a CompressedImage with the new background')
    assert images[-1].format == 'png'
    centre = _decode(images[-1]).getpixel(pixel(CENTER, CENTER))
    assert centre != (69, 86, 0)  # turtle1 is drawn
    response = ros.probe.call(Trigger, '/turtlesim/_save_canvas', Trigger.Request())
    assert not response.success
    assert 'cannot write' in response.message
    assert sim.running()
    assert 'Traceback' not in sim.output
    sim.stop()

    plain = ros.run('turtlesim', 'turtlesim_node', '--headless', '--ros-args', '-r', '__node:=plain')
    plain.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    ros.probe.wait_for_node('plain')
    wait_until(lambda: '/turtle1/pose' in dict(ros.probe.node.get_topic_names_and_types()), 10, 'topics')
    assert '/plain/canvas/compressed' not in dict(ros.probe.node.get_topic_names_and_types())


def _decode(message) -> Image.Image:
    return Image.open(io.BytesIO(bytes(message.data))).convert('RGB')


def test_without_headless_flag_runs_headless_when_no_display_can_be_opened(ros, tmp_path):
    # No windows' folder (the harness sets OWL_WINDOWS_DIR empty): no browser window either.
    no_display = ros.run('turtlesim', 'turtlesim_node', env={'DISPLAY': ''})
    no_display.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
    unreachable = ros.run('turtlesim', 'turtlesim_node', '--ros-args', '-r', '__node:=second',
                          env={'DISPLAY': ':4242'})
    unreachable.wait_for(r'\[WARN\].*\[second\]: No window \(.*\); running headless', timeout=30)
    assert ros.probe.get_parameters('second', 'background_r') == [69]  # serving
    # With the folder, the window that could not open goes to the browser (owl windows) instead.
    to_browser = ros.run('turtlesim', 'turtlesim_node', '--ros-args', '-r', '__node:=third',
                         env={'DISPLAY': ':4242', 'OWL_WINDOWS_DIR': str(tmp_path)})
    to_browser.wait_for(r'\[INFO\].*\[third\]: No display \(couldn.t connect to display ":4242"\): the '
                        r'TurtleSim window is shown in a browser instead\.', timeout=30)
    frame = tmp_path / f'turtlesim_node-{to_browser.pid}' / 'tk-TurtleSim.jpg'
    wait_until(frame.exists, 10, 'the first frame in the windows folder')
    assert Image.open(frame).size == (500, 500)
    for process in (no_display, unreachable, to_browser):
        process.stop_cleanly()
    assert 'No window' not in no_display.output + to_browser.output
    assert 'Traceback' not in no_display.output + unreachable.output + to_browser.output
    assert not frame.parent.exists()
