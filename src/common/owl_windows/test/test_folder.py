"""The windows folder's contract: its paths, key events and codes, the frame writer, the key reader."""

import os
import tempfile
import time
from pathlib import Path

import pytest
from owl_windows import folder as seam


@pytest.mark.parametrize(('argv', 'name'), [
    (['/ws/install/olive_camera/lib/olive_camera/display_camera'], 'display_camera'),
    (['my_viewer.py'], 'my_viewer'), (['-c'], 'python'), ([''], 'python'), ([], 'python'),
])
def test_program_name(argv, name):
    assert seam.program_name(argv) == name


def test_windows_go_to_the_users_own_folder_unless_said_otherwise(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, 'tempdir', str(tmp_path))
    assert seam.windows_root({}) == str(tmp_path / f'owl-windows-{os.getuid()}')
    assert seam.windows_root({'OWL_WINDOWS_DIR': '/w'}) == '/w'
    assert seam.windows_root({'OWL_WINDOWS_DIR': ''}) is None  # set and empty: no folder at all


def test_the_windows_root_is_private_and_never_someone_elses(tmp_path, monkeypatch):
    root = tmp_path / 'owl-windows'
    seam.private_root(str(root))
    assert root.stat().st_mode & 0o777 == 0o700
    seam.private_root(str(root))  # there already: fine
    someone_else = os.getuid() + 1
    monkeypatch.setattr(seam.os, 'getuid', lambda: someone_else)
    with pytest.raises(PermissionError, match='belongs to another user'):
        seam.private_root(str(root))


def test_window_files():
    assert seam.window_file('cv2', 'camera') == 'cv2-camera.jpg'
    assert seam.window_file('cv2', 'Camera 1/2') == 'cv2-Camera%201%2F2.jpg'
    assert seam.window_file('pygame', 'anything') == 'pygame.png'


@pytest.mark.parametrize(('line', 'event'), [
    ('down left', (True, 'left')), ('up left', (False, 'left')),
    ('  down left shift \n', (True, 'left shift')), ('down a', (True, 'a')),
])
def test_parse_key_event(line, event):
    assert seam.parse_key_event(line) == event


@pytest.mark.parametrize('line', ['press left', 'down', 'down ', 'left', '', 'DOWN left'])
def test_parse_key_event_refuses(line):
    with pytest.raises(ValueError, match="expected 'down <key>' or 'up <key>'"):
        seam.parse_key_event(line)


def test_cv2_key_codes_are_the_gui_builds():
    names = ('a', '1', 'space', 'return', 'escape', 'left', 'up', 'right', 'down', 'f1', 'f12', 'left shift')
    codes = {name: seam.cv2_key_code(name) for name in names}
    assert codes == {'a': 97, '1': 49, 'space': 32, 'return': 13, 'escape': 27, 'left': 0xff51, 'up': 0xff52,
                     'right': 0xff53, 'down': 0xff54, 'f1': 0xffbe, 'f12': 0xffc9, 'left shift': 0xffe1}
    assert [seam.cv2_key_code(n) & 0xff for n in ('left', 'up', 'right', 'down')] == [81, 82, 83, 84]
    assert seam.cv2_key_code('keypad 5') is None


def test_key_reader_reads_appended_lines_once_and_skips_bad_ones_with_one_line(tmp_path, capsys):
    keys = tmp_path / 'keys'
    reader = seam.KeyReader(str(keys), lambda key: key != 'bogus')
    assert reader.events() == []  # no file yet
    keys.write_text('down left\nup le')
    assert reader.events() == [(True, 'left')]
    with keys.open('a') as file:
        file.write('ft\ndown bogus\nsideways\n\ndown bogus\n')
    assert reader.events() == [(False, 'left')]
    assert reader.events() == []
    said = capsys.readouterr().err.splitlines()
    assert said == [
        f"owl_gui_hook: key event 'down bogus' in {keys} skipped: unknown key 'bogus'",
        f"owl_gui_hook: key event 'sideways' in {keys} skipped: expected 'down <key>' or 'up <key>'",
    ]
    keys.write_text('down a\n')  # truncated and written again: read from its start
    assert reader.events() == [(True, 'a')]


def test_windows_folder_writes_at_a_limited_rate_atomically_and_keeps_the_last_frame(tmp_path):
    written = []

    def encode(frame):
        written.append(frame)
        return f'frame {frame}'.encode()

    folder = seam.WindowsFolder(str(tmp_path), 'viewer', fps=20.0)
    assert folder.path == str(tmp_path / f'viewer-{os.getpid()}')
    for frame in range(5):  # within one period: the first now, the last later
        folder.show('cv2-camera.jpg', frame, encode, lambda f: f)
    path = Path(folder.path)
    assert sorted(p.name for p in path.iterdir()) == ['cv2-camera.jpg', 'keys']
    assert (path / 'cv2-camera.jpg').read_bytes() == b'frame 0'
    assert (path / 'keys').read_bytes() == b''
    folder.flush_due()
    assert written == [0]
    time.sleep(0.06)
    folder.flush_due()
    assert written == [0, 4]  # frames 1 to 3 were never encoded
    assert (path / 'cv2-camera.jpg').read_bytes() == b'frame 4'
    folder.discard('cv2-camera.jpg')
    assert sorted(p.name for p in path.iterdir()) == ['keys']
    folder.remove()
    assert not path.exists()


def test_windows_folder_that_cannot_be_made_is_said_once(tmp_path, capsys):
    (tmp_path / 'file').write_text('')
    folder = seam.WindowsFolder(str(tmp_path / 'file'), 'viewer', fps=10.0)
    folder.show('cv2-camera.jpg', 0, lambda f: b'', lambda f: f)
    folder.show('cv2-camera.jpg', 1, lambda f: b'', lambda f: f)
    [line] = capsys.readouterr().err.splitlines()
    assert line.startswith(f'owl_gui_hook: OWL_WINDOWS_DIR: cannot make {folder.path} (')
    assert line.endswith('): windows are not written there')
