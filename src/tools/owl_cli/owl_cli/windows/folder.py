"""The headless windows' folder as `owl windows` reads it (node-free).

Each running program with headless windows has a folder <root>/<program>-<pid>/ (owl_windows.folder
documents and writes it): cv2-<window>.jpg per
OpenCV window, pygame.png for a pygame display, tk-<window>.jpg for a window a program draws itself
(turtlesim's TurtleSim), and a `keys` file that the program reads key events from.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote

from owl_windows.folder import cv2_key_code, default_windows_dir, parse_key_event, private_root

__all__ = ['Window', 'append_key_event', 'default_windows_dir', 'private_root', 'scan']

PROCESS_FOLDER = re.compile(r'(?P<program>.+)-(?P<pid>\d+)')
JPEG_KINDS = ('cv2', 'tk')  # <kind>-<name>.jpg: OpenCV's windows, and those a program draws (turtlesim)
MAX_FRAME_BYTES = 16 * 1024 * 1024  # a 4K frame as PNG is under this; anything larger is not a frame


@dataclass(frozen=True)
class Window:
    """One headless window of a running program: whose it is, its kind and name, and its frame file."""

    program: str
    pid: int
    kind: str  # 'cv2', 'pygame' or 'tk'
    name: str  # the window's name as the program gave it ('pygame' for a pygame display)
    path: Path
    changed: int  # the file's mtime in ns: a new frame changes it

    @property
    def id(self) -> str:
        """How the page names it: <program>-<pid>/<file>."""
        return f'{self.path.parent.name}/{self.path.name}'

    @property
    def content_type(self) -> str:
        """The MIME type of the window's frames: PNG for a pygame display, JPEG for an OpenCV window."""
        return 'image/png' if self.kind == 'pygame' else 'image/jpeg'

    def summary(self) -> dict[str, object]:
        """The window as the page's list shows it (JSON-ready): id, program, pid, kind and name."""
        return {'id': self.id, 'program': self.program, 'pid': self.pid, 'kind': self.kind,
                'name': self.name}


def running(pid: int) -> bool:
    """Whether a process with this id exists (signal 0 asks without sending anything)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True  # someone else's process by that number: it runs
    return True


def window_of(path: Path, program: str, pid: int) -> Window | None:
    """The window a file of a program's folder shows; None for other files and one removed meanwhile."""
    name = path.name
    kind, _, rest = name.partition('-')
    if name == 'pygame.png':
        kind, title = 'pygame', 'pygame'
    elif kind in JPEG_KINDS and name.endswith('.jpg'):
        title = unquote(rest[:-len('.jpg')])
    else:
        return None  # the keys file, a frame being written (.<name>.tmp)
    try:
        changed = path.stat().st_mtime_ns
    except OSError:
        return None  # removed since the folder was listed
    return Window(program, pid, kind, title, path, changed)


def scan(root: Path) -> list[Window]:
    """Every window of a running program under root, ordered by program, pid and name.

    Folders of programs that ended without removing them (killed) are left out; [] when root cannot
    be read.
    """
    windows: list[Window] = []
    try:
        folders = list(root.iterdir())
    except OSError:
        return []
    for folder in folders:
        match = PROCESS_FOLDER.fullmatch(folder.name)
        if not match or not folder.is_dir() or not running(int(match['pid'])):
            continue
        program, pid = unquote(match['program']), int(match['pid'])
        try:
            files = sorted(folder.iterdir())
        except OSError:
            continue
        windows.extend(w for w in (window_of(f, program, pid) for f in files) if w is not None)
    return sorted(windows, key=lambda w: (w.program, w.pid, w.kind, w.name))


def read_frame(window: Window) -> bytes | None:
    """The window's latest frame, None if it went away (or is not a frame's size)."""
    try:
        if window.path.stat().st_size > MAX_FRAME_BYTES:
            return None
        return window.path.read_bytes()
    except OSError:
        return None


def key_event_line(event: str, key: str) -> str:
    """'down'/'up' and a pygame key name as a line of the keys file; ValueError for anything else.

    A key name is printable and on one line, and a key the windows know.
    """
    if not isinstance(event, str) or not isinstance(key, str):
        raise ValueError('event and key must be strings')
    if len(key) > 20 or not key.isprintable() or key != key.strip():
        raise ValueError(f'{key!r} is not a key name')
    down, name = parse_key_event(f'{event} {key}')
    if cv2_key_code(name) is None or (len(name) == 1 and not (name.isdigit() or 'a' <= name <= 'z')
                                      and name not in '-=[];\',./`\\'):
        raise ValueError(f"unknown key {key!r} (pygame's names: left, space, return, a, 1, f1, ...)")
    return f"{'down' if down else 'up'} {name}\n"


def append_key_event(window: Window, event: str, key: str) -> None:
    """Append one key event to the keys file of the window's program.

    ValueError for a bad event (see key_event_line); OSError when the program has gone.
    """
    line = key_event_line(event, key)
    keys = window.path.parent / 'keys'
    with open(keys, 'a', encoding='utf-8') as file:  # the program made it; it may be gone
        file.write(line)
