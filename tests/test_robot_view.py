"""robot_view over real DDS with the real kit processes, its page in Chromium (web_harness.py).

The model follows the servos, the mouse holds the IMU and the head follows it (imu_control_robot),
the camera shows at its rate, and bad input gets one line. docs/screenshots/robot_view.png is made
here.
"""

import math
import re
import signal
import socket
import statistics
import time
from typing import Any

import pytest
from geometry_msgs.msg import Quaternion
from olive_kit.description import IMU_NAMESPACE
from ros_harness import wait_until
from sensor_msgs.msg import Imu, JointState
from web_harness import PageSocket, free_port

URL_LINE = r'robot_view: open (http://127\.0\.0\.1:\d+/) in a browser \(Ctrl-C to quit\)'
IMU_TOPIC = f'/olive/imu/{IMU_NAMESPACE}/imu'
TRUE_ORIENTATION = f'/olive_imu_{IMU_NAMESPACE}_dcm_srv/true_orientation'
CAMERA_NODE = '/olive_camera_eye_dcm_srv'
MIN_FPS = 15.0  # the camera publishes 30 frames/s; the target is in bench/, this is "it streams"
LATENCY_SAMPLES = 6


def start_kit_and_view(ros: Any) -> str:
    """robot_view.launch.py (the kit with its IMU in command mode, and robot_view): the page's address."""
    launch = ros.command(['ros2', 'launch', 'robot_view', 'robot_view.launch.py', f'port:={free_port()}'],
                         label='robot_view.launch')
    return launch.wait_for(URL_LINE, timeout=60)[0].group(1)


def yaw_of(q: Any) -> float:
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def drag(page: Any, dx: float, dy: float = 0.0, steps: int = 10) -> None:
    """Hold the IMU block with the mouse and move it by dx, dy pixels."""
    start = page.evaluate('window.robotView.imuOnPage()')
    page.mouse.move(start['x'], start['y'])
    page.mouse.down()
    page.mouse.move(start['x'] + dx, start['y'] + dy, steps=steps)
    page.mouse.up()


@pytest.mark.whole_kit
def test_the_model_follows_the_kit_and_the_mouse_turns_the_head(ros, page):
    base = start_kit_and_view(ros)
    imu = ros.probe.collect(Imu, IMU_TOPIC)
    pan_joints = ros.probe.collect(JointState, '/olive/servo/pan/joint')
    robot = ros.run('olive_servo', 'imu_control_robot')
    robot.wait_for(r'torque enabled: pan, tilt', timeout=40)
    page.goto(base)
    page.wait_for_function('() => window.robotView.pan !== null && window.robotView.imu !== null',
                           timeout=20_000)

    # The model's pan follows the pan servo's joint: drag the IMU (yaw), the head turns, the model too.
    wait_until(lambda: imu and pan_joints, 20, 'IMU and joint messages')
    yaw_before = yaw_of(imu[-1].orientation)
    drag(page, 60)  # 0.01 rad a pixel: 0.6 rad of yaw
    wait_until(lambda: abs(yaw_of(imu[-1].orientation) - yaw_before - 0.6) < 0.05, 10,
               'the IMU turned 0.6 rad by the mouse')
    wait_until(lambda: abs(pan_joints[-1].position[0] - 0.6) < 0.05, 15, 'the pan servo at 0.6 rad')
    def model_at_joint() -> bool:
        return abs(page.evaluate('window.robotView.panOfModel()') - pan_joints[-1].position[0]) < 0.02
    wait_until(model_at_joint, 5, "the model's pan at the servo's joint")
    assert page.evaluate('window.robotView.commandsSent') > 0

    # "Level" puts the IMU back flat, and the head follows.
    page.click('#level')
    wait_until(lambda: abs(yaw_of(imu[-1].orientation)) < 0.05, 10, 'the IMU levelled')
    wait_until(lambda: abs(pan_joints[-1].position[0]) < 0.05, 15, 'the pan servo back at 0')

    # Latency: a drag to the pan servo's joint moving, split where the page's command reaches DDS
    # (page, WebSocket, robot_view | imu_sim, imu_control_robot, servo_sim).
    commands: list[float] = []
    probe = ros.probe.node
    probe.create_subscription(Quaternion, TRUE_ORIENTATION, lambda _: commands.append(time.monotonic()), 10)
    timed_joints: list[tuple[float, float]] = []
    probe.create_subscription(JointState, '/olive/servo/pan/joint',
                              lambda joint: timed_joints.append((time.monotonic(), joint.position[0])), 10)
    wait_until(lambda: timed_joints, 10, 'pan joints')
    to_command, to_moving = [], []
    for sample in range(LATENCY_SAMPLES):
        commands.clear()
        start_position = timed_joints[-1][1]
        grip = page.evaluate('window.robotView.imuOnPage()')
        page.mouse.move(grip['x'], grip['y'])
        page.mouse.down()
        started = time.monotonic()  # the one move that turns the IMU, as Playwright sends it
        page.mouse.move(grip['x'] + (20 if sample % 2 == 0 else -20), grip['y'])
        page.mouse.up()
        def moved(started: float = started, start_position: float = start_position) -> float | None:
            return next((t for t, position in timed_joints if t > started
                         and abs(position - start_position) > 0.01), None)
        wait_until(lambda: moved() is not None and commands, 10, 'the pan servo moving')
        to_command.append(commands[0] - started)
        moved_at = moved()
        assert moved_at is not None
        to_moving.append(moved_at - commands[0])
        time.sleep(0.5)
    for what, values in (('drag -> hold_imu on DDS', to_command),
                         ('hold_imu -> pan servo moving', to_moving),
                         ('drag -> pan servo moving',
                          [a + b for a, b in zip(to_command, to_moving, strict=True)])):
        print(f'{what}: p50 {statistics.median(values) * 1000:.0f} ms, max {max(values) * 1000:.0f} ms '
              f'({len(values)} drags)')

    # The camera, pushed: frames per second counted in the page. (No probe subscribes to the
    # camera here: a second subscriber of 30 images/s in this process cost the page 5-10 frames/s
    # on a busy machine.)
    page.wait_for_function('() => window.robotView.frames > 10', timeout=20_000)
    before = page.evaluate('[window.robotView.frames, window.robotView.lastFrame]')
    time.sleep(4.0)
    after = page.evaluate('[window.robotView.frames, window.robotView.lastFrame]')
    fps, taken = ((end - start) / 4.0 for start, end in zip(before, after, strict=True))
    print(f'camera in the page: {fps:.1f} frames/s; robot_view took {taken:.1f} frames/s from DDS')
    # A video's rate in the page. How close to the camera's 30 frames/s it stays is
    # bench/robot_view_smoothness.py's: a suite on 2 cores showed 21.5/s once (the camera itself fell
    # to 22.5/s), and 27.8/s while robot_view's count seemed to say 35/s (the page was 0.7 s behind
    # at the first look). Both numbers say which side of robot_view a drop is on.
    assert fps >= MIN_FPS, f'{fps:.1f} frames/s in the page; robot_view took {taken:.1f}/s from DDS'

    drag(page, 30, 25)  # a pose worth a picture
    time.sleep(2.0)
    page.screenshot_to('robot_view')


def test_bad_websocket_input_gets_one_line_and_nothing_reaches_the_imu(ros):
    base = start_kit_and_view(ros)
    held = ros.probe.collect(Quaternion, TRUE_ORIENTATION)
    # robot_view publishes each command once, on a volatile topic: until the probe knows its
    # publisher, a command would be lost to it, and "nothing reached" below would prove nothing.
    wait_until(lambda: ros.probe.node.count_publishers(TRUE_ORIENTATION) > 0, 20,
               "robot_view's publisher of the IMU's orientation")
    with PageSocket(base) as page_socket:
        bad_messages: list[tuple[dict[str, Any] | str, str]] = [
            ('{"type": "command", "id": 1, "name": "hold_imu", "orientation": {"x": NaN, "y": 0, "z": 0, '
             '"w": 1}}', 'the orientation: "x" must be finite, got nan'),
            ({'type': 'command', 'id': 2, 'name': 'hold_imu',
              'orientation': {'x': 1, 'y': 1, 'z': 1, 'w': 1}},
             'the orientation must be a unit quaternion (norm 1), got norm 2'),
            ({'type': 'command', 'id': 3, 'name': 'hold_imu', 'orientation': [0, 0, 0, 1]},
             'the orientation must be an object {"x", "y", "z", "w"}, got [0, 0, 0, 1]'),
            ({'type': 'command', 'id': 4, 'name': 'hold_imu'}, "missing key 'orientation'"),
            ({'type': 'command', 'id': 5, 'name': 'levle'},
             'unknown command "levle" (did you mean \'level\'?); known: goal, hold_imu, level, '
             'place_ball, set_gains, torque'),
            ({'type': 'command', 'id': 6, 'name': 'level', 'now': 1}, "unknown key 'now'; expected: "),
            ('{"type": "command", ', 'malformed JSON in the message: '),
            ({'type': 'comand', 'id': 7}, 'unknown message type "comand" (did you mean \'command\'?)'),
            ({'type': 'command', 'id': 8, 'name': 'place_ball', 'azimuth': 0.1}, "missing key 'elevation'"),
            ({'type': 'command', 'id': 9, 'name': 'place_ball', 'azimuth': 'left', 'elevation': 0},
             'the ball\'s azimuth must be a number, got "left"'),
            ('{"type": "command", "id": 10, "name": "place_ball", "azimuth": 0, "elevation": Infinity}',
             "the ball's elevation must be finite, got inf"),
            ({'type': 'command', 'id': 11, 'name': 'place_ball', 'azimuth': 0, 'elevation': 0},
             "the camera refused to put the ball there: there is no ball in the scene 'landmarks' (start "
             'the camera with scene:=ball)')]
        for message, error in bad_messages:
            page_socket.send(message)
            answer = page_socket.receive()
            assert answer['type'] == 'error', answer
            assert answer['error'].startswith(error), answer
            assert '\n' not in answer['error']
        time.sleep(1.0)
        assert held == []  # nothing reached the simulated IMU
        page_socket.send({'type': 'command', 'id': 'ok', 'name': 'level'})
        assert page_socket.receive() == {'type': 'done', 'id': 'ok'}
        wait_until(lambda: held and (held[-1].w, held[-1].z) == (1.0, 0.0), 10, 'the level command published')


def test_a_busy_port_and_a_bad_port_get_one_line(ros):
    with socket.socket() as busy:
        busy.bind(('127.0.0.1', 0))
        busy.listen(1)
        port = busy.getsockname()[1]
        taken = ros.command(['ros2', 'run', 'robot_view', 'robot_view', '--port', str(port)])
        assert taken.wait(timeout=30) == 1
        # one line of ours; `ros2 run` adds its own "[ros2run]: Process exited with failure 1"
        lines = [line for line in taken.output.strip().splitlines() if not line.startswith('[ros2run]')]
        assert len(lines) == 1, lines
        assert re.match(rf'robot_view: cannot serve on 127\.0\.0\.1:{port}: ', lines[0]), lines
    bad = ros.command(['ros2', 'run', 'robot_view', 'robot_view', '--port', 'eighty'])
    assert bad.wait(timeout=30) == 2
    assert "robot_view: error: argument --port: 'eighty' is not a port number (0..65535)" in bad.output
    assert 'Traceback' not in bad.output


def test_ctrl_c_stops_robot_view_cleanly(ros):
    view = ros.command(['ros2', 'run', 'robot_view', 'robot_view', '--port', '0'])
    view.wait_for(URL_LINE, timeout=30)
    # At once: the line comes just before rclpy spins, and a Ctrl-C in that gap used to interrupt
    # the executor's constructor (a traceback from its __del__; owl_common.run.spin_until_stopped).
    assert view.stop(timeout=10) == 0, view.output
    assert 'Traceback' not in view.output


def start_scene_and_view(ros: Any, *arguments: str) -> str:
    launch = ros.command(['ros2', 'launch', 'robot_view', 'robot_view.launch.py', f'port:={free_port()}',
                          *arguments], label='robot_view.launch')
    return launch.wait_for(URL_LINE, timeout=60)[0].group(1)


def ball_at_rest_on_page(page: Any) -> dict[str, float]:
    """Where the ball is on the page, once the page has stopped moving it there.

    The page's layout settles as its camera frames, plots and links arrive; a drag computed before
    a shift ends somewhere else (seen in two clean-clone runs). The kit line above the view is
    settled once the page knows every module runs.
    """
    page.wait_for_function('() => window.robotView.kit && Object.values(window.robotView.kit.modules)'
                           '.every(Boolean)', timeout=20_000)
    start = page.evaluate('window.robotView.ballOnPage()')
    deadline = time.monotonic() + 10
    while True:
        time.sleep(0.3)
        now = page.evaluate('window.robotView.ballOnPage()')
        if abs(now['x'] - start['x']) + abs(now['y'] - start['y']) < 0.5:
            return now
        assert time.monotonic() < deadline, f'the ball kept moving on the page: {start} then {now}'
        start = now


def drag_ball(page: Any, azimuth: float, elevation: float) -> dict[str, float]:
    """Drag the ball to that direction with the mouse from where it rests; returns the drop point."""
    start = ball_at_rest_on_page(page)
    target = page.evaluate(f'window.robotView.ballPlaceOnPage({azimuth}, {elevation})')
    page.mouse.move(start['x'], start['y'])
    page.mouse.down()
    page.mouse.move(target['x'], target['y'], steps=10)
    page.mouse.up()
    return target


@pytest.mark.whole_kit
def test_the_ball_is_shown_and_dragged_and_a_place_out_of_its_world_is_refused_in_one_line(ros, page):
    base = start_scene_and_view(ros, 'scene:=ball', 'ball_speed:=0.0')
    page.goto(base)
    page.wait_for_function('() => window.robotView.scene !== null && window.robotView.scene.ball',
                           timeout=30_000)
    assert page.evaluate('window.robotView.scene.ball') == [0.25, -0.12]
    # A state of the camera's that comes after the mouse let go but before the page's last place is
    # sent holds an earlier place (seen once in a clean-clone run: it pulled the ball back, and the
    # late send sent it from there). The page's timers stand still here, so the last place waits;
    # the probe puts the ball back where it started, as an earlier place.
    page.clock.install()
    ball_at_rest_on_page(page)
    page.clock.pause_at(page.evaluate('Date.now()') + 1000)
    dropped = drag_ball(page, -0.3, 0.1)
    assert page.evaluate('window.robotView.ballPlacesSent') == 1
    assert all(r.successful for r in ros.probe.set_parameters(CAMERA_NODE, ball_azimuth=0.25,
                                                              ball_elevation=-0.12))
    page.wait_for_function('() => window.robotView.scene.ball[0] === 0.25', polling=100, timeout=10_000)
    held = page.evaluate('window.robotView.ballOnPage()')
    assert abs(held['x'] - dropped['x']) + abs(held['y'] - dropped['y']) < 1, (held, dropped)
    page.clock.resume()
    camera = CAMERA_NODE

    def placed() -> bool:
        azimuth, elevation = ros.probe.get_parameters(camera, 'ball_azimuth', 'ball_elevation')
        return abs(azimuth + 0.3) < 0.02 and abs(elevation - 0.1) < 0.02
    sent = ('window.robotView.ballPlacesSent + " places sent, answers "'
            ' + JSON.stringify(window.robotView.ballAnswers)')
    try:
        wait_until(placed, 10, 'the ball put at (-0.3, 0.1) rad by the mouse')
    except AssertionError as failure:
        where = ros.probe.get_parameters(camera, 'ball_azimuth', 'ball_elevation')
        raise AssertionError(f'{failure}; the camera has it at {where}; '
                             f'the page: {page.evaluate(sent)}') from None
    page.wait_for_function('() => Math.abs(window.robotView.scene.ball[0] + 0.3) < 0.02', timeout=10_000)
    assert page.evaluate('window.robotView.ballAnswers').count(None) > 0
    # Above the ball's world (elevation 0.6 at most): the camera says no, in one line on the page.
    page.evaluate("window.robotView.ballAnswers.length = 0")
    drag_ball(page, -0.3, 1.0)
    page.wait_for_function('() => window.robotView.ballAnswers.some((answer) => answer)', timeout=10_000)
    error = page.text_content('#errors')
    assert error.startswith('the camera refused to put the ball there: '), error
    assert 'ball_elevation' in error, error
    assert '\n' not in error, error
    assert abs(ros.probe.get_parameters(camera, 'ball_elevation')[0]) <= 0.6
    page.screenshot_to('robot_view_ball')


@pytest.mark.whole_kit
def test_the_person_is_shown_with_the_gesture_of_the_camera(ros, page):
    base = start_scene_and_view(ros, 'scene:=person', 'gesture:=both_hands_up')
    page.goto(base)
    page.wait_for_function('() => window.robotView.scene !== null && window.robotView.scene.keypoints',
                           timeout=30_000)
    assert page.evaluate('window.robotView.scene.gesture') == 'both_hands_up'
    assert len(page.evaluate('Object.keys(window.robotView.scene.keypoints)')) == 17
    assert page.evaluate('window.robotView.personParts()') == 18  # 17 bones and the head
    changed = ros.probe.set_parameters(CAMERA_NODE, gesture='hands_on_hip')
    assert all(r.successful for r in changed)
    page.wait_for_function("() => window.robotView.scene.gesture === 'hands_on_hip'", timeout=10_000)
    page.screenshot_to('robot_view_person')


def test_without_a_kit_the_page_says_what_to_start_and_after_its_server_stops_it_says_it_is_frozen(ros, page):
    view = ros.run('robot_view', 'robot_view', '--port', str(free_port()))
    page.goto(view.wait_for(URL_LINE, timeout=30)[0].group(1))
    # No module at all: one line names the commands that start the kit, the camera says it has none,
    # and "Level the IMU" cannot be pressed.
    page.wait_for_function("() => document.getElementById('kit-state').textContent.startsWith("
                           "'No Owl Kit module runs in this ROS domain')", timeout=20_000)
    assert 'ros2 launch robot_view robot_view.launch.py' in page.inner_text('#kit-state')
    assert 'ros2 launch olive_sim owl_kit.launch.py' in page.inner_text('#kit-state')
    assert page.is_visible('#camera-missing')
    assert not page.is_visible('#camera')  # no broken-image icon
    assert page.inner_text('#camera-missing').startswith('No camera runs. Start the kit:')
    assert page.is_disabled('#level')
    assert page.inner_text('#imu-hint') == 'No IMU runs: the block has nothing to hold.'
    page.screenshot_to('robot_view_no_kit')
    page.screenshot_at_390('robot_view_no_kit', '#kit-state')

    # An IMU that follows its own script (as in owl_kit.launch.py): dragging cannot steer it, and the
    # hint says so and how to start one that can be held.
    ros.run('olive_sim', 'imu_sim')
    page.wait_for_function("() => document.getElementById('kit-state').textContent.startsWith("
                           "'Not running: pan, tilt, camera')", timeout=20_000)
    wait_until(lambda: 'follows its own motion' in page.inner_text('#imu-hint'), 10, 'the scripted IMU hint')
    assert 'dragging the block does nothing' in page.inner_text('#imu-hint')
    assert page.is_disabled('#level')

    # robot_view dies (killed: no goodbye, the WebSocket's code 1006): the page greys out what it shows
    # and says, in words, that it is frozen.
    view.send_signal(signal.SIGKILL)
    view.wait(timeout=10)
    page.wait_for_function("() => document.body.classList.contains('stale')", timeout=10_000)
    status = page.inner_text('#status')
    assert status.startswith("lost the connection to this page's server (did it stop?)"), status
    assert 'What the page shows is frozen' in status
    assert 'code 1006' not in status
    page.screenshot_to('robot_view_server_stopped')
    page.screenshot_at_390('robot_view_server_stopped', '#status')
    page.goto('about:blank')  # no more reconnecting
    page.forgive_server_away()


def no_sideways_scroll(page: Any) -> bool:
    return page.evaluate('document.documentElement.scrollWidth <= window.innerWidth')


@pytest.mark.whole_kit
def test_the_view_fills_the_window_turns_and_zooms_and_works_on_a_phone_with_touch(ros, page):
    base = start_kit_and_view(ros)
    held = ros.probe.collect(Quaternion, TRUE_ORIENTATION)
    page.set_viewport_size({'width': 1920, 'height': 1080})
    page.goto(base)
    page.wait_for_function('() => window.robotView.imu !== null && window.robotView.frames > 3',
                           timeout=30_000)
    # A wide window is used: the 3D view and the camera grow with it (they were 600 and 400 px).
    wait_until(lambda: page.evaluate("document.querySelector('#model canvas').clientWidth") > 1000, 10,
               'the 3D view over half of a 1920 px window')
    assert page.evaluate("document.getElementById('camera').clientWidth") > 600
    assert no_sideways_scroll(page)
    page.screenshot_to('robot_view_1920')

    # Dragging the background turns the view round the robot; the wheel zooms in.
    box = page.locator('#model canvas').bounding_box()
    before = page.evaluate('window.robotView.cameraPosition()')
    distance = page.evaluate('window.robotView.cameraDistance()')
    page.mouse.move(box['x'] + 30, box['y'] + 30)
    page.mouse.down()
    page.mouse.move(box['x'] + 230, box['y'] + 60, steps=10)
    page.mouse.up()
    assert page.evaluate('window.robotView.cameraPosition()') != before
    assert page.evaluate('window.robotView.cameraDistance()') == pytest.approx(distance, rel=0.02)
    page.mouse.move(box['x'] + box['width'] / 2, box['y'] + box['height'] / 2)
    page.mouse.wheel(0, -400)
    wait_until(lambda: page.evaluate('window.robotView.cameraDistance()') < 0.9 * distance, 5, 'zoomed in')
    # Holding the IMU block turns the IMU, not the view.
    turned = page.evaluate('window.robotView.cameraPosition()')
    held.clear()
    drag(page, 80)
    wait_until(lambda: len(held) >= 3, 10, 'the held IMU orientations')
    assert page.evaluate('window.robotView.cameraPosition()') == turned

    # A phone: one column, nothing wider than the screen, and a finger holds the IMU without the
    # browser taking the gesture over (no pointercancel after a few moves).
    page.set_viewport_size({'width': 390, 'height': 844})
    wait_until(lambda: no_sideways_scroll(page), 10, 'the page within 390 px')
    assert page.evaluate("document.querySelector('#model canvas').clientWidth") <= 390
    page.screenshot_to('robot_view_390')
    page.evaluate("() => { window.cancelled = 0; document.querySelector('#model canvas')"
                  ".addEventListener('pointercancel', () => { window.cancelled += 1; }); }")
    start = page.evaluate('window.robotView.imuOnPage()')
    sent = page.evaluate('window.robotView.commandsSent')
    touch = page.context.new_cdp_session(page.page)
    point = {'x': start['x'], 'y': start['y']}
    touch.send('Input.dispatchTouchEvent', {'type': 'touchStart', 'touchPoints': [point]})
    for step in range(1, 16):
        touch.send('Input.dispatchTouchEvent', {'type': 'touchMove', 'touchPoints': [
            {'x': start['x'] + 4 * step, 'y': start['y']}]})
        time.sleep(0.03)
    touch.send('Input.dispatchTouchEvent', {'type': 'touchEnd', 'touchPoints': []})
    assert page.evaluate('window.cancelled') == 0
    assert page.evaluate('window.robotView.commandsSent') - sent >= 10, 'the finger did not hold the IMU'
