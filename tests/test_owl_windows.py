"""`owl windows` with real programs without a display, shown live on the page in Chromium.

A student's OpenCV viewer and pygame key reader (tests/student_scripts/) show on the page, live; keys
pressed on the page reach the pygame program; turtlesim's TurtleSim window is there too, driven by the
arrow keys and the on-screen arrows; bad input gets one line.
docs/screenshots/owl_windows.png and owl_windows_turtlesim(_390).png are made here.
"""

import re
import sys
import time
from pathlib import Path
from typing import Any

import pytest
from desktop import NO_DISPLAY
from ros_harness import wait_until
from turtlesim.msg import Pose
from web_harness import PageSocket, free_port

STUDENT_SCRIPTS = Path(__file__).parent / 'student_scripts'
URL_LINE = (r'owl windows: open (http://127\.0\.0\.1:\d+/) in a browser: the windows of programs without '
            r'a display \(from (.+)\); Ctrl-C to quit')


def start_windows_page(ros, folder):
    page_server = ros.command(['owl', 'windows', '--port', str(free_port()), '--folder', str(folder)],
                              label='owl windows')
    match = page_server.wait_for(URL_LINE, timeout=30)[0]
    assert match.group(2) == str(folder)
    return page_server, match.group(1)


def student(ros, script, folder):
    # The folder as the programs find it by default: TMPDIR/owl-windows-<uid>.
    return ros.command([sys.executable, str(STUDENT_SCRIPTS / script)], label=script,
                       env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(folder)})


def frames_of(page, program):
    return int(page.evaluate(
        f"() => Number(document.querySelector('[data-window^=\"{program}-\"]')?.dataset.frames ?? 0)"))


def test_windows_of_programs_without_a_display_show_live_and_get_the_keys_pressed(ros, page, tmp_path):
    folder = tmp_path / 'windows'
    page_server, url = start_windows_page(ros, folder)
    page.goto(url)
    page.wait_for_selector('#none:not([hidden])', timeout=10_000)  # nothing open yet, and it says so

    viewer = student(ros, 'cv2_viewer.py', folder)
    keys = student(ros, 'pygame_keys.py', folder)
    page.wait_for_function('() => document.body.dataset.windows === "2"', timeout=30_000)
    titles = page.locator('.window h2').all_inner_texts()
    assert any(re.fullmatch(rf"cv2_viewer \({viewer.pid}\) — 'camera'\s*", t) for t in titles), titles
    assert any(re.fullmatch(rf'pygame_keys \({keys.pid}\) — pygame window\s*', t) for t in titles), titles
    # The viewer draws a new image every frame: the page shows them as they come (10 a second at most).
    wait_until(lambda: frames_of(page, 'cv2_viewer') >= 10, 20, 'ten frames of the viewer on the page')
    width = "() => document.querySelector('[data-window^=\"cv2_viewer-\"] img').naturalWidth"
    assert page.evaluate(width) == 160

    # Keys pressed on the pygame window's card reach the program, held until released.
    page.click('[data-window^="pygame_keys-"]')
    page.keyboard.down('ArrowLeft')
    keys.wait_for(r'^held: left$', timeout=10)
    page.keyboard.up('ArrowLeft')
    keys.wait_for(r'^held: none$', timeout=10)
    page.keyboard.press('a')  # not an arrow: the program ignores it, the page sends it all the same
    page.screenshot_to('owl_windows')

    # A program that ends takes its window off the page.
    viewer.stop_cleanly(timeout=10)
    page.wait_for_function('() => document.body.dataset.windows === "1"', timeout=10_000)
    keys.stop_cleanly(timeout=10)
    assert [line for line in keys.lines if re.fullmatch(r'(down|up|held:) .*', line)] == [
        'down left', 'held: left', 'up left', 'held: none']
    page.wait_for_selector('#none:not([hidden])', timeout=10_000)
    page_server.stop_cleanly(timeout=10)
    assert 'Traceback' not in page_server.output


PIXEL_OF_WINDOW = """([program, x, y]) => {
  const image = document.querySelector(`[data-window^="${program}-"] img`);
  const canvas = document.createElement('canvas');
  canvas.width = image.naturalWidth;
  canvas.height = image.naturalHeight;
  const context = canvas.getContext('2d');
  context.drawImage(image, 0, 0);
  return Array.from(context.getImageData(x, y, 1, 1).data.slice(0, 3));
}"""
TURTLESIM_BLUE = (69, 86, 255)
PEN = (179, 184, 255)  # turtle1's pen


def near(colour, wanted, tolerance=24):
    return all(abs(a - b) <= tolerance for a, b in zip(colour, wanted, strict=True))


def test_turtlesim_without_a_display_shows_on_the_page_and_its_arrows_drive_turtle1(ros, page, tmp_path):
    folder = tmp_path / 'windows'
    page_server, url = start_windows_page(ros, folder)
    turtlesim = ros.run('turtlesim', 'turtlesim_node', env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(folder)})
    turtlesim.wait_for(r"No display: the TurtleSim window is shown in a browser instead\. Run 'owl windows' "
                       r'and open the page it prints; arrow keys pressed there drive '
                       r'turtle1\.$', timeout=30)
    poses = ros.probe.collect(Pose, '/turtle1/pose')
    page.goto(url)
    page.wait_for_function('() => document.body.dataset.windows === "1"', timeout=30_000)
    assert re.fullmatch(rf"turtlesim_node \({turtlesim.pid}\) — 'TurtleSim'\s*",
                        page.locator('.window h2').inner_text())
    card = '[data-window^="turtlesim_node-"]'
    page.wait_for_function(f"() => document.querySelector('{card} img').naturalWidth === 500", timeout=20_000)
    assert near(page.evaluate(PIXEL_OF_WINDOW, ['turtlesim_node', 10, 10]), TURTLESIM_BLUE)
    on_the_way = ['turtlesim_node', 340, 250]  # between the middle and where the turtle stops
    assert near(page.evaluate(PIXEL_OF_WINDOW, on_the_way), TURTLESIM_BLUE)

    # A malformed line in the keys file is said once and skipped; the turtle stays where it is.
    keys_file = folder / f'turtlesim_node-{turtlesim.pid}' / 'keys'
    with open(keys_file, 'a') as keys:
        keys.write('sideways up\n')
    turtlesim.wait_for(r"^owl_gui_hook: key event 'sideways up' in .* skipped: expected 'down <key>'",
                       timeout=10)

    # The up arrow held on the window: turtle1 goes forward at teleop's 2 m/s, and the page shows it live.
    def wait_for_pose(condition, what):
        wait_until(lambda: poses and condition(poses[-1]), 10, what)

    wait_for_pose(lambda pose: pose.x == pytest.approx(5.544, abs=0.01), 'turtle1 in the middle')
    page.click(card)
    frames_before = frames_of(page, 'turtlesim_node')
    page.keyboard.down('ArrowUp')
    wait_for_pose(lambda pose: pose.linear_velocity == 2.0, 'turtle1 driving forward')
    time.sleep(0.8)
    page.keyboard.up('ArrowUp')
    wait_for_pose(lambda pose: pose.linear_velocity == 0.0, 'turtle1 stopped, 1 s after the key')
    assert poses[-1].x > 8.0, poses[-1]
    assert poses[-1].theta == 0.0, poses[-1]
    assert frames_of(page, 'turtlesim_node') - frames_before >= 10, 'the page did not follow the turtle'
    wait_until(lambda: near(page.evaluate(PIXEL_OF_WINDOW, on_the_way), PEN), 10, 'the trail on the page')

    # The on-screen left arrow, held with the mouse (a finger on a phone): turtle1 turns left.
    page.hover(f'{card} .arrow.left')
    page.mouse.down()
    wait_for_pose(lambda pose: pose.angular_velocity == 2.0, 'turtle1 turning left')
    page.mouse.up()
    page.screenshot_to('owl_windows_turtlesim')
    page.set_viewport_size({'width': 390, 'height': 844})
    page.wait_for_function(f"() => document.querySelector('{card}').getBoundingClientRect().right <= 390")
    page.screenshot_to('owl_windows_turtlesim_390')

    turtlesim.stop_cleanly(timeout=10)
    page.wait_for_function('() => document.body.dataset.windows === "0"', timeout=10_000)
    assert not keys_file.parent.exists(), 'turtlesim left its window folder behind'
    page_server.stop_cleanly(timeout=10)
    # The page without its server says so in words, not as a WebSocket code.
    page.wait_for_function("() => document.body.classList.contains('stale')", timeout=10_000)
    assert 'The windows below are frozen; run owl windows again.' in page.inner_text('#status')
    page.goto('about:blank')
    page.forgive_server_away()


def test_bad_input_gets_one_line_and_nothing_reaches_the_program(ros, tmp_path):
    folder = tmp_path / 'windows'
    _, url = start_windows_page(ros, folder)
    keys = student(ros, 'pygame_keys.py', folder)
    keys_file = folder / f'pygame_keys-{keys.pid}' / 'keys'
    wait_until(keys_file.exists, 30, "the program's keys file")
    window = f'pygame_keys-{keys.pid}/pygame.png'
    with PageSocket(url) as page_socket:
        page_socket.subscribe(1, 'windows')
        page_socket.receive_matching(lambda m: m.get('id') == 1 and m['data']['windows'], 'the window list')
        bad_commands: list[tuple[dict[str, Any], str]] = [
            ({'name': 'key', 'window': window, 'event': 'sideways', 'key': 'left'},
             "expected 'down <key>' or 'up <key>'"),
            ({'name': 'key', 'window': window, 'event': 'down', 'key': 'left\ndown right'},
             "'left\\ndown right' is not a key name"),
            ({'name': 'key', 'window': window, 'event': 'down', 'key': 'nokey'}, "unknown key 'nokey'"),
            ({'name': 'key', 'window': 'someone-1/pygame.png', 'event': 'down', 'key': 'left'},
             "no window 'someone-1/pygame.png'; open now: "),
            ({'name': 'key', 'window': 7, 'event': 'down', 'key': 'left'},
             "'window' must be a window's id"),
            ({'name': 'key', 'window': window, 'event': 'down'}, "missing key 'key'"),
            ({'name': 'key', 'window': window, 'event': 'down', 'key': 'left', 'x': 1},
             "unknown key 'x'"),
            ({'name': 'press'}, 'unknown command "press"')]
        for number, (message, error) in enumerate(bad_commands):
            page_socket.send({'type': 'command', 'id': number, **message})
            answer = page_socket.receive_matching(lambda m, n=number: m.get('id') == n, f'answer {number}')
            assert answer['type'] == 'error', answer
            assert answer['error'].startswith(error), answer
        page_socket.subscribe(20, 'window', window='../../etc/passwd')
        answer = page_socket.receive_matching(lambda m: m.get('id') == 20, 'the refused subscription')
        assert answer['error'].startswith("no window '../../etc/passwd'"), answer
        page_socket.send('{"type": "command", ')
        answer = page_socket.receive_matching(lambda m: m.get('type') == 'error' and m['id'] is None,
                                              'the error for malformed JSON')
        assert answer['error'].startswith('malformed JSON'), answer
        page_socket.send({'type': 'command', 'id': 'ok', 'name': 'key', 'window': window, 'event': 'down',
                          'key': 'left'})
        done = page_socket.receive_matching(lambda m: m.get('id') == 'ok', 'the good command done')
        assert done == {'type': 'done', 'id': 'ok'}
    assert keys_file.read_text() == 'down left\n'  # only the good one reached the program
    keys.wait_for(r'^held: left$', timeout=10)


def test_bad_arguments_and_a_busy_port_get_one_line(ros, tmp_path):
    bad = ros.command(['owl', 'windows', '--port', 'eighty'])
    assert bad.wait(timeout=20) == 2
    assert "owl windows: error: argument --port: 'eighty' is not a port number (0..65535)" in bad.output
    assert 'Traceback' not in bad.output
    (tmp_path / 'file').write_text('')
    not_a_folder = ros.command(['owl', 'windows', '--port', '0', '--folder', str(tmp_path / 'file')])
    assert not_a_folder.wait(timeout=20) == 1
    assert not_a_folder.lines == [f'owl windows: cannot use {tmp_path / "file"}: File exists'], \
        not_a_folder.output
