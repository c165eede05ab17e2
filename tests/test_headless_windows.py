"""Windows without a display: a student's cv2 and pygame programs, run as real processes.

Without a display each says so in one line, runs on, and stops cleanly at Ctrl-C; with
OWL_WINDOWS_DIR its windows' latest images go to files and key events come from a file (the seam
of src/tools/owl_venv_hooks/owl_gui_hook.py). Under Xvfb the same programs open real windows and
the hook stays out of the way. tests/student_scripts/ holds the programs, written as the course writes them.
"""

import os
import re
import sys
import time
from pathlib import Path

import cv2
import numpy as np
from desktop import NO_DISPLAY, REAL_WINDOWS
from ros_harness import wait_until

STUDENT_SCRIPTS = Path(__file__).parent / 'student_scripts'
CV2_NOTICE = ("cv2_viewer: no display (DISPLAY is not set), so the window 'camera' is not shown; the "
              "program runs on without it. To see it in a browser, run 'owl windows'")
PYGAME_NOTICE = ('pygame_keys: no display (neither DISPLAY nor WAYLAND_DISPLAY is set), so the pygame '
                 'window is not shown and gets no key presses; the program runs on without them. To see '
                 "it and press its keys in a browser, run 'owl windows'")
PYGAME_GREETING = re.compile(r'pygame \d+\.\d+\.\d+ \(SDL|Hello from the pygame community')
RED = (0, 0, 255)  # BGR


def student(ros, script, env):
    return ros.command([sys.executable, str(STUDENT_SCRIPTS / script)], label=script, env=env)


def own_lines(process):
    """The process's output without pygame's greeting at import."""
    return [line for line in process.lines if not PYGAME_GREETING.match(line)]


def append(path, *lines):
    with path.open('a') as file:
        file.write(''.join(f'{line}\n' for line in lines))


def read_image(path):
    """The image in a seam file, or None while there is none (files are replaced atomically)."""
    return cv2.imread(str(path)) if path.exists() else None


def close_to(pixel, colour, tolerance=30):
    return int(np.abs(pixel.astype(int) - colour).max()) < tolerance


def default_folder(tmp_path, process):
    """Where a process's windows go without OWL_WINDOWS_DIR: the user's own folder in TMPDIR."""
    return tmp_path / f'owl-windows-{os.getuid()}' / f'{Path(process.label).stem}-{process.pid}'


def test_cv2_viewer_without_a_display_says_so_in_one_line_runs_on_and_stops_at_ctrl_c(ros, tmp_path):
    viewer = student(ros, 'cv2_viewer.py', {**NO_DISPLAY, 'TMPDIR': str(tmp_path)})
    viewer.wait_for('no display', timeout=30)
    time.sleep(1.0)  # runs on: a second is some 700 frames on a busy 2-core machine, 100 needed below
    assert viewer.running(), viewer.output
    folder = default_folder(tmp_path, viewer)
    assert (folder / 'cv2-camera.jpg').exists()  # for `owl windows`, which reads the same folder
    assert folder.parent.stat().st_mode & 0o777 == 0o700  # only this user sees the windows
    viewer.stop_cleanly(timeout=10)
    notice, summary = viewer.lines
    assert notice == f'{CV2_NOTICE} (its frames go to {folder})'
    shown = re.fullmatch(r'shown (\d+) frames', summary)
    assert shown, summary
    assert int(shown[1]) > 100  # waitKey(1) waited about 1 ms


def test_cv2_viewer_seam_gets_the_latest_frames_and_sends_keys(ros, tmp_path):
    viewer = student(ros, 'cv2_viewer.py', {**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    folder = tmp_path / f'cv2_viewer-{viewer.pid}'
    frame_file = folder / 'cv2-camera.jpg'
    wait_until(frame_file.exists, 30, 'the first frame in the seam')
    # The notice comes first, but the harness reads it from a pipe: on a busy machine it was not read
    # yet when the frame was there.
    viewer.wait_for(re.escape(CV2_NOTICE), timeout=10)
    assert viewer.lines == [f'{CV2_NOTICE} (its frames go to {folder})']
    frame = read_image(frame_file)
    assert frame.shape == (120, 160, 3)
    assert close_to(frame[60, 40], RED)
    greys: set[int] = set()

    def three_greys_seen() -> bool:
        greys.add(int(read_image(frame_file)[60, 120, 0]) // 16)
        return len(greys) >= 3

    # the image changes with every frame: the file follows
    wait_until(three_greys_seen, 10, 'three different frames')
    append(folder / 'keys', 'down left', 'up left', 'down a', 'down escape', 'down nokey', 'sideways')
    viewer.wait_for(r'^key 27$', timeout=10)
    viewer.stop_cleanly(timeout=10)
    keys = [line for line in viewer.lines if line.startswith('key ')]
    assert keys == ['key 81', 'key 97', 'key 27']  # waitKey's low byte of the GUI build's codes
    keys_file = folder / 'keys'
    assert f"owl_gui_hook: key event 'down nokey' in {keys_file} skipped: unknown key 'nokey'" in viewer.lines
    assert (f"owl_gui_hook: key event 'sideways' in {keys_file} skipped: expected 'down <key>' or "
            "'up <key>'") in viewer.lines
    assert 'Traceback' not in viewer.output
    assert not folder.exists()  # the process's windows are gone with it


def test_bad_settings_are_said_in_one_line_each_and_ignored(ros, tmp_path):
    viewer = student(ros, 'cv2_viewer.py', {**NO_DISPLAY, 'OWL_HEADLESS': 'maybe', 'OWL_WINDOWS_FPS': 'fast',
                                            'OWL_WINDOWS_DIR': str(tmp_path)})
    viewer.wait_for('no display', timeout=30)
    viewer.stop_cleanly(timeout=10)
    assert viewer.lines[:3] == [
        "owl_gui_hook: OWL_HEADLESS must be 1 (no windows) or 0 (real windows), not 'maybe': ignored",
        "owl_gui_hook: OWL_WINDOWS_FPS must be a number of frames per second above 0, not 'fast': using 10",
        f'{CV2_NOTICE} (its frames go to {tmp_path / f"cv2_viewer-{viewer.pid}"})',
    ]
    assert len(viewer.lines) == 4


def test_pygame_keys_without_a_display_says_so_in_one_line_runs_on_and_stops_at_ctrl_c(ros, tmp_path):
    keys = student(ros, 'pygame_keys.py', {**NO_DISPLAY, 'TMPDIR': str(tmp_path)})
    keys.wait_for('no display', timeout=30)
    time.sleep(1.0)  # runs on: a second is some 75 loops on a busy 2-core machine, 20 needed below
    assert keys.running(), keys.output
    keys.stop_cleanly(timeout=10)
    notice, summary = own_lines(keys)
    keys_file = default_folder(tmp_path, keys) / 'keys'
    assert notice == f"{PYGAME_NOTICE}; or append key events to {keys_file} ('down left', 'up left')"
    ran = re.fullmatch(r'ran (\d+) loops', summary)
    assert ran, summary
    assert int(ran[1]) > 20
    assert 'ALSA' not in keys.output  # SDL on its dummy drivers
    assert 'XDG' not in keys.output


def test_pygame_keys_seam_sends_key_events_and_held_keys_and_gets_the_window(ros, tmp_path):
    keys = student(ros, 'pygame_keys.py', {**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    folder = tmp_path / f'pygame_keys-{keys.pid}'
    window = folder / 'pygame.png'
    wait_until(window.exists, 30, 'the window in the seam')
    # The program prints its notice before it writes the image, but this test reads the notice
    # through a pipe and a reader thread: the file can be seen first.
    wait_until(lambda: bool(own_lines(keys)), 10, "the program's notice")
    assert own_lines(keys) == [f"{PYGAME_NOTICE}; or append key events to {folder / 'keys'} ('down left', "
                               "'up left')"]
    assert read_image(window).shape == (80, 200, 3)  # black at first: set_mode's empty window
    wait_until(lambda: close_to(read_image(window)[40, 100], (0, 0, 128), 5), 10, 'the window turning red')
    append(folder / 'keys', 'down left')
    keys.wait_for(r'^held: left$', timeout=10)
    # What the program drew while the key was held (green) reaches the file.
    wait_until(lambda: close_to(read_image(window)[40, 100], (0, 128, 0), 5), 10, 'the window turning green')
    append(folder / 'keys', 'down up')
    keys.wait_for(r'^held: left up$', timeout=10)
    append(folder / 'keys', 'up left', 'up up')
    keys.wait_for(r'^held: none$', timeout=10)
    keys.stop_cleanly(timeout=10)
    events = [line for line in own_lines(keys) if re.fullmatch(r'(down|up|held:) .*', line)]
    assert events == ['down left', 'held: left', 'down up', 'held: left up', 'up left', 'up up', 'held: none']
    assert not folder.exists()


def test_a_students_display_camera_without_a_display_runs_on_the_camera_and_stops_at_ctrl_c(ros, tmp_path):
    ros.run('olive_sim', 'camera_sim')
    camera = student(ros, 'student_display_camera.py', {**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    folder = tmp_path / f'student_display_camera-{camera.pid}'
    frame_file = folder / f"cv2-{'Olive%20Camera'}.jpg"
    wait_until(frame_file.exists, 60, "the camera's first image in the seam")
    assert read_image(frame_file).shape == (480, 640, 3)
    # It runs on: 30 frames shown (its own log line), where a line that came with every frame would show.
    camera.wait_for(r'\]: 30 frames shown$', timeout=30)
    camera.stop_cleanly(timeout=10)
    assert [line for line in camera.lines if 'frames shown' not in line] == [
        "student_display_camera: no display (DISPLAY is not set), so the window 'Olive Camera' is not shown; "
        "the program runs on without it. To see it in a browser, run 'owl windows' "
        f'(its frames go to {folder})']


def test_cv2_viewer_with_a_display_opens_a_real_window_that_gets_keys(ros, x_display, tmp_path):
    viewer = student(ros, 'cv2_viewer.py',
                     {**x_display.env(), **REAL_WINDOWS, 'OWL_WINDOWS_DIR': str(tmp_path)})
    window = x_display.wait_for_window('^camera$', timeout=30)
    # A window that has just appeared may not take keys yet (a first Left was lost once, with the
    # focus set): Left again until it arrives, then a.
    for attempt in range(1, 6):
        x_display.type(window, 'Left')
        try:
            viewer.wait_for(r'^key 81$', timeout=2)
            break
        except AssertionError:
            if attempt == 5:
                raise
    x_display.type(window, 'a')
    viewer.wait_for(r'^key 97$', timeout=10)
    viewer.stop_cleanly(timeout=10)
    # No notice, nothing from Qt (its font warnings are silenced): the keys and the summary.
    assert viewer.lines[:2] == ['key 81', 'key 97'], viewer.output
    assert len(viewer.lines) == 3, viewer.output
    assert list(tmp_path.iterdir()) == []  # nothing patched: no seam


def test_pygame_keys_with_a_display_opens_a_real_window_that_gets_keys(ros, x_display, tmp_path):
    # This machine may have no sound card; ALSA's complaints about it are not under test here.
    keys = student(ros, 'pygame_keys.py', {**x_display.env(), **REAL_WINDOWS,
                                           'OWL_WINDOWS_DIR': str(tmp_path), 'SDL_AUDIODRIVER': 'dummy'})
    window = x_display.wait_for_window('^keys$', timeout=30)
    x_display.type(window, 'Left')
    keys.wait_for(r'^up left$', timeout=10)
    keys.stop_cleanly(timeout=10)
    assert 'no display' not in keys.output
    assert [line for line in own_lines(keys) if line.startswith(('down', 'up'))] == ['down left', 'up left']
    assert list(tmp_path.iterdir()) == []


def test_owl_headless_1_makes_windows_headless_on_a_display_too(ros, x_display, tmp_path):
    forced = {**x_display.env(), 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': '1',
              'OWL_WINDOWS_DIR': str(tmp_path)}
    viewer = student(ros, 'cv2_viewer.py', forced)
    keys = student(ros, 'pygame_keys.py', forced)
    viewer.wait_for(r"^cv2_viewer: no display \(OWL_HEADLESS=1\), so the window 'camera' is not", timeout=30)
    keys.wait_for(r'^pygame_keys: no display \(OWL_HEADLESS=1\), so the pygame window is not', timeout=30)
    wait_until((tmp_path / f'cv2_viewer-{viewer.pid}' / 'cv2-camera.jpg').exists, 10, 'the seam')
    # The notice comes from inside set_mode, before the program's try: a Ctrl-C there is a traceback
    # of the student's own (seen once on a busy machine). The window drawn red is its loop running.
    keys_window = tmp_path / f'pygame_keys-{keys.pid}' / 'pygame.png'
    red = (0, 0, 128)
    wait_until(lambda: keys_window.exists() and close_to(read_image(keys_window)[40, 100], red, 5), 10,
               'the keys program in its loop (its window red)')
    assert x_display.windows('^(camera|keys)$') == []
    viewer.stop_cleanly(timeout=10)
    keys.stop_cleanly(timeout=10)


def test_a_seam_key_is_held_only_from_the_event_pump_that_delivers_its_keydown(ros, tmp_path):
    # As with SDL's own keyboard state: a key pressed after the loop took its events shows as held
    # only once an event function has pumped its KEYDOWN, never in get_pressed() before it.
    order = student(ros, 'pygame_key_order.py', {**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(tmp_path)})
    assert order.wait(30) == 0, order.output
    assert re.search(r'^KEYDOWN, then held, at loop 6$', order.output, re.M), order.output
