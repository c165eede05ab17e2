"""The TurtleSim window without a display: frames into the windows' folder, keys held from its page."""

from __future__ import annotations

import os

import pytest
from PIL import Image
from turtlesim_py.arrow_keys import held_drive
from turtlesim_py.browser_window import FILE_NAME, BrowserWindow


def test_the_arrows_drive_as_turtle_teleop_key_does():
    assert held_drive(set()) is None
    assert held_drive({'a', 'space'}) is None  # not arrows: nothing to drive
    assert held_drive({'up'}) == (2.0, 0.0)
    assert held_drive({'down'}) == (-2.0, 0.0)
    assert held_drive({'left'}) == (0.0, 2.0)
    assert held_drive({'right'}) == (0.0, -2.0)
    assert held_drive({'up', 'left'}) == (2.0, 2.0)  # a left curve
    assert held_drive({'up', 'down'}) == (0.0, 0.0)  # held against each other: standing still
    assert held_drive({'up'}, scale_linear=0.5) == (0.5, 0.0)


@pytest.fixture
def folder(tmp_path, monkeypatch):
    monkeypatch.setenv('OWL_WINDOWS_DIR', str(tmp_path))
    return tmp_path


def test_frames_go_to_the_windows_folder_and_leave_with_the_window(folder):
    window = BrowserWindow.open()
    assert window is not None
    assert os.path.dirname(window.path) == str(folder)
    assert window.path.endswith(f'-{os.getpid()}')  # <program>-<pid>, as `owl windows` reads it
    window.show(Image.new('RGB', (500, 500), (69, 86, 255)))
    frame = Image.open(os.path.join(window.path, FILE_NAME))
    assert frame.format == 'JPEG'
    assert frame.size == (500, 500)
    assert all(abs(a - b) <= 4 for a, b in zip(frame.convert('RGB').getpixel((250, 250)), (69, 86, 255),
                                                strict=True))
    window.close()
    assert not os.path.exists(window.path)


def test_keys_from_the_page_are_held_until_let_go_and_bad_lines_are_said_and_skipped(folder, capsys):
    window = BrowserWindow.open()
    assert window is not None
    keys = os.path.join(window.path, 'keys')
    with open(keys, 'a') as file:
        file.write('down up\ndown left\nsideways up\n')
    window.pump()
    assert window.held_keys() == {'up', 'left'}
    with open(keys, 'a') as file:
        file.write('up left\n')
    window.pump()
    assert window.held_keys() == {'up'}
    assert "key event 'sideways up'" in capsys.readouterr().err
    window.close()


def test_no_folder_means_no_browser_window(monkeypatch, tmp_path):
    monkeypatch.setenv('OWL_WINDOWS_DIR', '')  # set and empty: no headless windows anywhere
    assert BrowserWindow.open() is None
    not_a_folder = tmp_path / 'file'
    not_a_folder.write_text('')
    monkeypatch.setenv('OWL_WINDOWS_DIR', str(not_a_folder))
    assert BrowserWindow.open() is None  # said in one line by the hook, never a traceback
