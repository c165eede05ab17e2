"""The headless windows' folder as `owl windows` reads it: which windows, their frames, key lines."""

import os
import subprocess
import sys

import pytest
from owl_cli.windows.folder import append_key_event, key_event_line, read_frame, scan


def ended_pid() -> int:
    """The number of a process that has ended."""
    process = subprocess.run([sys.executable, '-c', 'import os; print(os.getpid())'], capture_output=True,
                             text=True, check=True)
    return int(process.stdout)


@pytest.fixture
def root(tmp_path):
    live = tmp_path / f'display%20camera-{os.getpid()}'
    live.mkdir()
    (live / 'cv2-Olive%20Camera.jpg').write_bytes(b'jpeg')
    (live / 'pygame.png').write_bytes(b'png')
    (live / 'tk-TurtleSim.jpg').write_bytes(b'jpeg')
    (live / 'tk-notes.txt').write_bytes(b'not a frame')
    (live / '.pygame.png.tmp').write_bytes(b'half')
    (live / 'keys').write_text('')
    dead = tmp_path / f'killed-{ended_pid()}'
    dead.mkdir()
    (dead / 'cv2-camera.jpg').write_bytes(b'old')
    (tmp_path / 'not-a-process').mkdir()
    (tmp_path / f'file-{os.getpid()}').write_text('')
    return tmp_path


def test_scan_lists_the_windows_of_running_programs_only(root):
    windows = scan(root)
    assert [(w.program, w.pid, w.kind, w.name) for w in windows] == [
        ('display camera', os.getpid(), 'cv2', 'Olive Camera'),
        ('display camera', os.getpid(), 'pygame', 'pygame'),
        ('display camera', os.getpid(), 'tk', 'TurtleSim')]
    assert windows[0].id == f'display%20camera-{os.getpid()}/cv2-Olive%20Camera.jpg'
    assert [w.content_type for w in windows] == ['image/jpeg', 'image/png', 'image/jpeg']
    assert read_frame(windows[0]) == b'jpeg'


def test_scan_of_a_folder_that_is_not_there_is_empty(tmp_path):
    assert scan(tmp_path / 'missing') == []


def test_a_frame_gone_since_the_scan_reads_as_none(root):
    window = scan(root)[0]
    window.path.unlink()
    assert read_frame(window) is None


@pytest.mark.parametrize(('event', 'key', 'line'), [
    ('down', 'left', 'down left\n'), ('up', 'left shift', 'up left shift\n'), ('down', 'a', 'down a\n'),
    ('down', '7', 'down 7\n'), ('down', 'f12', 'down f12\n'), ('up', 'space', 'up space\n')])
def test_key_event_lines(event, key, line):
    assert key_event_line(event, key) == line


@pytest.mark.parametrize(('event', 'key', 'problem'), [
    ('sideways', 'left', "expected 'down <key>'"), ('down', 'nokey', 'unknown key'),
    ('down', 'left\ndown right', 'is not a key name'), ('down', 'A', 'unknown key'),
    ('down', '', "expected 'down <key>'"), ('down', ' left', 'is not a key name'),
    ('down', 'x' * 100, 'is not a key name'), ('down', 5, 'must be strings'),
    (None, 'left', 'must be strings')])
def test_bad_key_events_are_refused(event, key, problem):
    with pytest.raises(ValueError, match=problem):
        key_event_line(event, key)


def test_key_events_go_to_the_programs_keys_file(root):
    window = scan(root)[1]
    append_key_event(window, 'down', 'left')
    append_key_event(window, 'up', 'left')
    assert (window.path.parent / 'keys').read_text() == 'down left\nup left\n'
    with pytest.raises(ValueError, match='unknown key'):
        append_key_event(window, 'down', 'nokey')
    assert (window.path.parent / 'keys').read_text() == 'down left\nup left\n'  # nothing half-written


def test_a_key_for_a_program_that_has_gone_is_an_os_error(root):
    window = scan(root)[0]
    for path in window.path.parent.iterdir():
        path.unlink()
    window.path.parent.rmdir()
    with pytest.raises(FileNotFoundError):
        append_key_event(window, 'down', 'left')
