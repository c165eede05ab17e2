"""Unit tests of owl_gui_hook.py's pure parts and of its headless cv2 on a stand-in module.

The module is loaded from its source beside test/ (the copy in the venv is what processes run; tests/
runs those).
Its headless pygame needs SDL in a process of its own: tests/test_headless_windows.py.
"""

import importlib.util
import os
import time
import types
from pathlib import Path

import cv2
import numpy
import pytest

SOURCE = Path(__file__).resolve().parents[1] / 'owl_gui_hook.py'
spec = importlib.util.spec_from_file_location('owl_gui_hook_under_test', SOURCE)
hook = importlib.util.module_from_spec(spec)
spec.loader.exec_module(hook)


@pytest.mark.parametrize(('environ', 'cv2_reason', 'pygame_reason'), [
    ({}, 'DISPLAY is not set', 'neither DISPLAY nor WAYLAND_DISPLAY is set'),
    ({'DISPLAY': ''}, 'DISPLAY is not set', 'neither DISPLAY nor WAYLAND_DISPLAY is set'),
    ({'DISPLAY': ':0'}, None, None),
    ({'WAYLAND_DISPLAY': 'wayland-0'}, "DISPLAY is not set, and OpenCV's windows need X11 (XWayland)", None),
    ({'DISPLAY': ':0', 'OWL_HEADLESS': '1'}, 'OWL_HEADLESS=1', 'OWL_HEADLESS=1'),
    ({'OWL_HEADLESS': '0'}, None, None),
    ({'DISPLAY': ':0', 'OWL_HEADLESS': 'yes'}, None, None),  # ignored (and said: setting_problems)
])
def test_headless_reason(environ, cv2_reason, pygame_reason):
    assert hook.headless_reason('cv2', environ) == cv2_reason
    assert hook.headless_reason('pygame', environ) == pygame_reason


def test_ignored_settings_are_named_with_what_is_used_instead():
    assert hook.setting_problems({}) == []
    assert hook.setting_problems({'OWL_HEADLESS': '1', 'OWL_WINDOWS_FPS': '2.5'}) == []
    [headless] = hook.setting_problems({'OWL_HEADLESS': 'yes'})
    assert headless == "OWL_HEADLESS must be 1 (no windows) or 0 (real windows), not 'yes': ignored"
    for fps in ('fast', '0', '-3', 'inf', 'nan'):
        [problem] = hook.setting_problems({'OWL_WINDOWS_FPS': fps})
        assert problem == (f'OWL_WINDOWS_FPS must be a number of frames per second above 0, not {fps!r}: '
                           'using 10'), fps
        assert hook.windows_fps({'OWL_WINDOWS_FPS': fps}) == 10.0
    assert hook.windows_fps({'OWL_WINDOWS_FPS': '25'}) == 25.0



def test_notices_say_what_happened_and_where_to_look_instead():
    line = hook.cv2_notice('display_camera', 'DISPLAY is not set', 'camera', None)
    assert line == ("display_camera: no display (DISPLAY is not set), so the window 'camera' is not shown; "
                    'the program runs on without it. To see the camera, run rqt and open Plugins > '
                    'Visualization > Image View')
    assert hook.cv2_notice('v', 'r', 'camera', '/w/v-1').endswith(
        "the program runs on without it. To see it in a browser, run 'owl windows' (its frames go to /w/v-1)")
    line = hook.pygame_notice('keyboard_servos', 'OWL_HEADLESS=1', None)
    assert line.startswith('keyboard_servos: no display (OWL_HEADLESS=1), so the pygame window is not '
                           'shown and gets no key presses; the program runs on without them.')
    assert '/olive/servo/pan/goal/position' in line
    assert 'setTorqueEnable' in line
    line = hook.pygame_notice('keyboard_servos', 'OWL_HEADLESS=1', '/w/keyboard_servos-7')
    assert line.endswith("the program runs on without them. To see it and press its keys in a browser, run "
                         "'owl windows'; or append key events to /w/keyboard_servos-7/keys ('down left', "
                         "'up left')")
    assert '\n' not in line


def test_displayable_is_what_imshow_shows():
    grey = numpy.full((2, 3), 7, numpy.uint8)
    assert hook.displayable(grey) is grey
    assert hook.displayable(numpy.full((2, 3), 0x1234, numpy.uint16)).tolist() == [[0x12] * 3] * 2
    floats = numpy.array([[-0.5, 0.0, 0.5, 1.0, 2.0, numpy.nan]], numpy.float32)
    assert hook.displayable(floats).tolist() == [[0, 0, 127, 255, 255, 0]]
    assert hook.displayable(numpy.array([[300, -4]], numpy.int32)).tolist() == [[255, 0]]
    bgra = numpy.zeros((2, 2, 4), numpy.uint8)
    bgra[..., 3] = 255
    assert hook.displayable(bgra).shape == (2, 2, 3)
    assert hook.displayable(numpy.zeros((2, 2, 1), numpy.uint8)).shape == (2, 2)
    for shape in ((4,), (2, 2, 2), (2, 2, 3, 1)):
        with pytest.raises(ValueError, match='cannot be shown'):
            hook.displayable(numpy.zeros(shape, numpy.uint8))


# --- headless cv2 on a stand-in module: what the patch does to cv2's functions -------------------

@pytest.fixture
def headless_cv2(tmp_path, monkeypatch):
    """A module with cv2's window functions, patched as a process without a display gets them."""
    monkeypatch.setenv('OWL_WINDOWS_DIR', str(tmp_path))
    monkeypatch.setenv('OWL_WINDOWS_FPS', '1000')
    monkeypatch.setattr(hook.sys, 'argv', ['viewer.py'])
    window_functions = ('imshow', 'namedWindow', 'waitKey', 'waitKeyEx', 'pollKey', 'destroyWindow',
                        'destroyAllWindows', 'resizeWindow', 'getWindowProperty', 'setMouseCallback',
                        'createTrackbar', 'getTrackbarPos')
    fake = types.SimpleNamespace(
        error=cv2.error, UMat=cv2.UMat, imencode=cv2.imencode, IMWRITE_JPEG_QUALITY=cv2.IMWRITE_JPEG_QUALITY,
        WND_PROP_VISIBLE=cv2.WND_PROP_VISIBLE, WND_PROP_AUTOSIZE=cv2.WND_PROP_AUTOSIZE,
        **dict.fromkeys(window_functions))
    hook.patch_cv2(fake, 'DISPLAY is not set')
    fake.folder = tmp_path / f'viewer-{os.getpid()}'
    return fake


def test_headless_imshow_says_it_once_and_writes_the_frame(headless_cv2, capsys):
    image = numpy.zeros((30, 40, 3), numpy.uint8)
    image[:, :20] = (0, 0, 255)
    headless_cv2.imshow('camera', image)
    headless_cv2.imshow('camera', image)
    headless_cv2.imshow('other', image)
    [line] = capsys.readouterr().err.splitlines()
    assert line.startswith("viewer: no display (DISPLAY is not set), so the window 'camera' is not shown")
    written = cv2.imread(str(headless_cv2.folder / 'cv2-camera.jpg'))
    assert written.shape == (30, 40, 3)
    assert numpy.abs(written[:, 5].astype(int) - (0, 0, 255)).max() < 30
    assert headless_cv2.getWindowProperty('camera', cv2.WND_PROP_VISIBLE) == 1.0
    headless_cv2.resizeWindow('camera', 10, 10)  # accepted, nothing to do
    headless_cv2.destroyWindow('camera')
    assert headless_cv2.getWindowProperty('camera', cv2.WND_PROP_VISIBLE) == 0.0
    assert not (headless_cv2.folder / 'cv2-camera.jpg').exists()
    headless_cv2.destroyAllWindows()
    assert sorted(p.name for p in headless_cv2.folder.iterdir()) == ['keys']


@pytest.mark.parametrize(('image', 'message'), [
    (None, 'not a numpy array'), (numpy.zeros((0, 4), numpy.uint8), 'size.width>0 && size.height>0'),
    (numpy.zeros((4, 4, 2), numpy.uint8), 'cannot be shown'),
])
def test_headless_imshow_refuses_what_imshow_refuses(headless_cv2, image, message):
    with pytest.raises(cv2.error, match=message):
        headless_cv2.imshow('camera', image)


def test_headless_wait_key_waits_its_delay_and_returns_injected_keys(headless_cv2):
    headless_cv2.namedWindow('camera')
    started = time.monotonic()
    assert headless_cv2.waitKey(150) == -1
    assert 0.14 < time.monotonic() - started < 1.0
    assert headless_cv2.pollKey() == -1
    with (headless_cv2.folder / 'keys').open('a') as keys:
        keys.write('down left\nup left\ndown a\ndown escape\ndown right\n')
    assert headless_cv2.waitKey(0) == 81          # the low byte, at once
    assert headless_cv2.waitKeyEx(1000) == 97     # ups are ignored
    assert headless_cv2.waitKey(1) == 27
    assert headless_cv2.pollKey() == 0xff53       # the full code
    started = time.monotonic()
    assert headless_cv2.waitKey(50) == -1
    with (headless_cv2.folder / 'keys').open('a') as keys:
        keys.write('down space\n')
    assert headless_cv2.waitKey(5000) == 32
    assert time.monotonic() - started < 1.0


def test_headless_wait_key_zero_without_a_keys_file_says_ctrl_c_stops_it(monkeypatch, capsys):
    monkeypatch.setenv('OWL_WINDOWS_DIR', '')  # no windows' folder
    monkeypatch.setattr(hook.sys, 'argv', ['viewer.py'])
    fake = types.SimpleNamespace(error=cv2.error, UMat=cv2.UMat, waitKey=None, imshow=None)
    hook.patch_cv2(fake, 'DISPLAY is not set')
    slept = []

    def sleep(seconds):
        slept.append(seconds)
        if len(slept) == 3:
            raise KeyboardInterrupt  # Ctrl-C during the wait

    monkeypatch.setattr(time, 'sleep', sleep)
    with pytest.raises(KeyboardInterrupt):
        fake.waitKey(0)
    [line] = capsys.readouterr().err.splitlines()
    assert line == ('viewer: cv2.waitKey(0) waits for a key press, which no window can receive here: '
                    'Ctrl-C stops the program')
