"""The robot of `owl demo`: started in a sandbox, reported in readable lines, stopped with Ctrl-C's signal.

The command's options and its description are owl_cli/demo/command.py's.
"""

from __future__ import annotations

import math
import socket
import sys
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from contextlib import suppress
from dataclasses import dataclass, field
from functools import partial

import cv2
import numpy as np
from olive_kit.description import (
    BALL_COLOUR,
    CAMERA_TOPIC,
    IMU_TOPIC,
    ROBOT_VIEW_PORT,
    WINDOWS_PORT,
    goal_topic,
    joint_topic,
)
from owl_common import quaternion, ros_env
from owl_common.images import find_colour
from owl_common.probe import Probe
from owl_common.processes import RosProcess, RosSandbox
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import CompressedImage, Imu, JointState
from std_msgs.msg import Float32
from turtlesim.msg import Pose

SERVOS = ('pan', 'tilt')
STARTUP_TIMEOUT = 60.0  # s for every node to say it is working, on a loaded 2-core machine
# The page's address: under the front door (its root, then the page's mount), or its own.
ROBOT_VIEW_LINE = r'robot_view: open (http://127\.0\.0\.1:\d+/)(robot-view/)? in a browser'
WINDOWS_LINE = r'owl windows: open (http://127\.0\.0\.1:\d+/)(windows/)? in a browser'
# The tracking project's ball swings to and fro in front of the robot, BALL_SWING rad to either side
# of where the kit puts it (0.25 rad left), passing the middle at BALL_SPEED rad/s: the pan servo
# (+-1.57 rad) can follow it the whole time. (Going round, it passed the pan's limit after 9 s.)
BALL_SPEED = 0.2
BALL_SWING = 0.9
KIT_WITH_BALL = ('ros2', 'launch', 'olive_sim', 'owl_kit.launch.py', 'scene:=ball',
                 f'ball_speed:={BALL_SPEED}', f'ball_swing:={BALL_SWING}')


@dataclass
class RobotState:
    """The latest of everything the demo reports, filled by the probe's subscriptions."""

    euler: tuple[float, float, float] | None = None  # the IMU's last usable (roll, pitch, yaw)
    goals: dict[str, float] = field(default_factory=dict)
    positions: dict[str, float] = field(default_factory=dict)
    frames: int = 0
    frame: bytes | None = None  # the camera's latest JPEG
    pose: Pose | None = None


def watch(probe: Probe) -> RobotState:
    """Subscribe the probe to the IMU, both servos, the camera and the turtle."""
    state = RobotState()

    def on_imu(msg: Imu) -> None:
        q = msg.orientation
        euler = quaternion.usable_euler((q.x, q.y, q.z, q.w))
        if euler is not None:
            state.euler = euler

    def on_frame(msg: CompressedImage) -> None:
        state.frames += 1
        state.frame = msg.data

    def on_pose(msg: Pose) -> None:
        state.pose = msg

    def on_goal(servo: str, msg: Float32) -> None:
        state.goals[servo] = msg.data

    def on_joint(servo: str, msg: JointState) -> None:
        state.positions[servo] = msg.position[0]

    node = probe.node
    node.create_subscription(Imu, IMU_TOPIC, on_imu, qos_profile_sensor_data)
    node.create_subscription(CompressedImage, CAMERA_TOPIC, on_frame, qos_profile_sensor_data)
    node.create_subscription(Pose, '/turtle1/pose', on_pose, 10)
    for servo in SERVOS:
        node.create_subscription(Float32, goal_topic(servo), partial(on_goal, servo), 10)
        node.create_subscription(JointState, joint_topic(servo), partial(on_joint, servo), 10)
    return state


def degrees(radians: float) -> str:
    """An angle for the report: radians as signed whole degrees, e.g. ' +12°'."""
    return f'{math.degrees(radians):+4.0f}°'


def ball_offset(jpeg: bytes) -> tuple[float, float] | None:
    """Where the red ball is in a camera image: (right, down) of the middle as shares of width and height."""
    bgr = cv2.imdecode(np.frombuffer(bytes(jpeg), np.uint8), cv2.IMREAD_COLOR)
    if bgr is None:
        return None
    ball = find_colour(cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB), BALL_COLOUR)
    if ball is None:
        return None
    height, width = bgr.shape[:2]
    return (ball[0] - (width - 1) / 2) / width, (ball[1] - (height - 1) / 2) / height


def tracking_text(state: RobotState) -> str:
    """The tracking error of the latest camera image, for a report line."""
    offset = ball_offset(state.frame) if state.frame is not None else None
    if offset is None:
        return 'ball not in sight'
    right, down = offset
    return f'ball {100 * right:+5.1f} % right, {100 * down:+5.1f} % down of the middle'


def report_line(elapsed: float, state: RobotState, fps: float, project: str = 'imu') -> str:
    """One line of what the robot does now."""
    parts = [f'{elapsed:3.0f} s']
    if project == 'tracking':
        parts.append(tracking_text(state))
    elif state.euler is not None:
        roll, pitch, yaw = state.euler
        parts.append(f'IMU roll {degrees(roll)} pitch {degrees(pitch)} yaw {degrees(yaw)}')
    for servo in SERVOS:
        goal, position = state.goals.get(servo), state.positions.get(servo)
        goal_text = f'{goal:+.2f}' if goal is not None else '--'
        position_text = f'{position:+.2f}' if position is not None else '--'
        parts.append(f'{servo} goal {goal_text} at {position_text} rad')
    parts.append(f'camera {fps:4.1f} fps')
    if state.pose is not None:
        parts.append(f'turtle ({state.pose.x:.1f}, {state.pose.y:.1f}) heading {degrees(state.pose.theta)}')
    return ' | '.join(parts)


def page_port(preferred: int) -> int:
    """The port to give a page's server: the preferred one when it is free on 127.0.0.1, else 0.

    A robot_view, an owl windows or another demo may hold the preferred port; with 0, the server picks
    a free one and prints it.
    """
    with socket.socket() as probe:
        try:
            probe.bind(('127.0.0.1', preferred))
        except OSError:
            return 0
    return preferred


def serve_page(start: Callable[[int], RosProcess], preferred: int, line: str) -> RosProcess:
    """A page's server started with start(port) on the preferred port, or on any free one.

    The preferred port may be free when looked at and taken a moment later (a second demo starting
    beside this one): a server that says it cannot serve there is started again on port 0.
    """
    server = start(page_port(preferred))
    if 'cannot serve on' in server.wait_for(f'{line}|cannot serve on', STARTUP_TIMEOUT)[0].group(0):
        server.wait()
        server = start(0)
        server.wait_for(line, STARTUP_TIMEOUT)
    return server


def start_robot(sandbox: RosSandbox, project: str = 'imu') -> dict[str, RosProcess]:
    """The kit, the course's projects and robot_view, each waited for until it says it works."""
    if project == 'tracking':
        return start_tracking_robot(sandbox)
    processes = {
        'kit': sandbox.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py'], label='kit'),
        'imu_turtle': sandbox.command(['ros2', 'launch', 'olive_imu', 'imu_turtle.launch.py'],
                                      label='imu_turtle'),
        'imu_control_robot': sandbox.run('olive_servo', 'imu_control_robot'),
        'display_camera': sandbox.run('olive_camera', 'display_camera'),
        'robot_view': serve_page(robot_view_on(sandbox), ROBOT_VIEW_PORT, ROBOT_VIEW_LINE),
        'owl_windows': serve_page(owl_windows_on(sandbox), WINDOWS_PORT, WINDOWS_LINE),
    }
    processes['imu_control_robot'].wait_for(r'steering the pan and tilt servos', STARTUP_TIMEOUT)
    processes['imu_turtle'].wait_for(r'IMU data on', STARTUP_TIMEOUT)
    processes['display_camera'].wait_for(r'showing them in the window', STARTUP_TIMEOUT)
    return processes


def robot_view_on(sandbox: RosSandbox) -> Callable[[int], RosProcess]:
    """start(port) for serve_page: robot_view in the sandbox on that port."""
    return lambda port: sandbox.run('robot_view', 'robot_view', '--port', str(port))


def owl_windows_on(sandbox: RosSandbox) -> Callable[[int], RosProcess]:
    """start(port) for serve_page: `owl windows` in the sandbox on that port."""
    return lambda port: sandbox.command(['owl', 'windows', '--port', str(port)], label='owl windows')


def start_tracking_robot(sandbox: RosSandbox) -> dict[str, RosProcess]:
    """Section 4.6's robot: the kit with a red ball going round, track_object and display_camera."""
    processes = {
        'kit': sandbox.command(list(KIT_WITH_BALL), label='kit'),
        'track_object': sandbox.run('olive_vision', 'track_object'),
        'display_camera': sandbox.run('olive_camera', 'display_camera'),
        'robot_view': serve_page(robot_view_on(sandbox), ROBOT_VIEW_PORT, ROBOT_VIEW_LINE),
    }
    processes['track_object'].wait_for(r'red ball at .* tracking it', STARTUP_TIMEOUT)
    processes['display_camera'].wait_for(r'showing them in the window', STARTUP_TIMEOUT)
    return processes


def page_address(process: RosProcess, line: str) -> tuple[str, bool]:
    """Where a page's server said to open it, and whether that is the front door's root.

    (the front door's root, True) when the page joined the front door, else (its own address, False).
    """
    match = process.wait_for(line, 1.0)[0]
    return match.group(1), match.group(2) is not None


def print_pages(processes: dict[str, RosProcess], project: str = 'imu') -> None:
    """Where to watch: the front door, one address for every page; each page's own without one."""
    robot_view, front_door = page_address(processes['robot_view'], ROBOT_VIEW_LINE)
    windows = 'owl_windows' in processes
    hint = ('the IMU follows its script here' if project == 'imu'
            else 'drag the red ball elsewhere and the head follows it')
    if front_door:
        turtle = (", windows (the TurtleSim window and display_camera's, when they have no display)"
                  if windows else '')
        print(f'== pages: open {robot_view} in a browser: the robot view (the kit in 3D, live plots, the '
              f"camera; {hint}){turtle}, each module's own page; `owl pages` lists them", flush=True)
        return
    print(f'== robot view: open {robot_view} in a browser (the kit in 3D, live plots, the camera; {hint})',
          flush=True)
    if windows:
        print(f"== turtlesim: open {page_address(processes['owl_windows'], WINDOWS_LINE)[0]} in a browser "
              "(owl windows: the TurtleSim window and display_camera's window, when they have no display)",
              flush=True)


def display_camera_lines(process: RosProcess) -> list[str]:
    """What display_camera said about its window: where it shows the camera, or that it cannot."""
    return [line for line in process.lines if 'showing them in the window' in line or 'no display' in line]


def stop_all(processes: dict[str, RosProcess]) -> dict[str, int]:
    """Stop every process (SIGINT, as Ctrl-C would); each one's exit code.

    All but the kit stop side by side, none waiting for another's goodbye; the kit stops last, as the
    servos' torque is switched off through it.
    """
    others = {label: process for label, process in processes.items() if label != 'kit'}
    with ThreadPoolExecutor(len(others)) as pool:
        codes = dict(zip(others, pool.map(RosProcess.stop, others.values()), strict=True))
    codes['kit'] = processes['kit'].stop()
    return codes


def run_demo(seconds: float, report_every: float, project: str = 'imu') -> int:
    """Run the demo for seconds, a status line every report_every s; the exit code, 0 if all stopped cleanly.

    Each process is stopped with SIGINT at the end; any exit code but 0 makes it 1, with that process's
    last lines on stderr.
    """
    # env.sh's network mode: private (LOCALHOST) unless the user opened it with OWL_NETWORK=open.
    # The user's pages folder: the demo's pages join the user's front door (it stays when the demo ends).
    with RosSandbox(discovery_range=ros_env.discovery_range(), private_pages=False) as sandbox:
        print(f'== Owl Kit Lab demo: the simulated Owl Kit and the course\'s chapter 4 projects, '
              f'ROS 2 domain {sandbox.domain_id}, {seconds:.0f} s', flush=True)
        if project == 'tracking':
            print('   kit: IMU, servos pan and tilt, camera eye, and a red ball swinging '
                  f'{math.degrees(BALL_SWING):.0f}° to either side in front of the robot '
                  f"({' '.join(KIT_WITH_BALL)})\n"
                  '   track_object: the head keeps the ball in the middle of the picture (section 4.6)\n'
                  '   display_camera: the camera\'s picture', flush=True)
        else:
            print('   kit: IMU, servos pan and tilt, camera eye (ros2 launch olive_sim owl_kit.launch.py)\n'
                  '   imu_control_robot: the head points where the IMU points\n'
                  '   display_camera: the camera\'s picture\n'
                  '   imu_turtle: the IMU drives turtlesim\'s turtle (pitch = speed, yaw = turning)',
                  flush=True)
        print(f'== watch it from another shell: source env.sh && export ROS_DOMAIN_ID={sandbox.domain_id}, '
              'then `rqt` (Plugins > Visualization > Image View, '
              f'topic {CAMERA_TOPIC}) or `ros2 topic echo /turtle1/pose`', flush=True)
        probe = Probe(sandbox.domain_id, 'owl_demo')
        try:
            state = watch(probe)
            processes = start_robot(sandbox, project)
            # Without a display, display_camera says so right after its first frame's line; with one, not.
            with suppress(AssertionError):
                processes['display_camera'].wait_for(r': no display \(', 0.5)
            for line in display_camera_lines(processes['display_camera']):
                print(f'   display_camera says: {line}', flush=True)
            print_pages(processes, project)
            print('== running', flush=True)
            start = last = time.monotonic()
            frames_then = state.frames
            while (now := time.monotonic()) - start < seconds:
                time.sleep(min(report_every, start + seconds - now))
                now = time.monotonic()
                fps = (state.frames - frames_then) / max(now - last, 1e-6)
                frames_then, last = state.frames, now
                print('   ' + report_line(now - start, state, fps, project), flush=True)
        finally:
            probe.close()
        print('== stopping (SIGINT, as Ctrl-C would)', flush=True)
        codes = stop_all(processes)
    failed = {label: code for label, code in codes.items() if code != 0}
    if failed:
        print(f'== demo finished with errors (exit codes): {failed}', file=sys.stderr)
        for label in failed:
            print(f'-- last lines of {label}:\n{processes[label].tail(15)}', file=sys.stderr)
        return 1
    print('== demo finished: every node stopped cleanly', flush=True)
    return 0
