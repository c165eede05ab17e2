"""The windows folder: the seam between programs without a display and `owl windows`.

Headless windows (the venv's start-up hook makes cv2's and pygame's so; turtlesim draws its own)
write what they show to files in a folder and read key events from a file there; `owl windows`
serves them as a page and appends the keys pressed on it. This module is that contract, in one
place for all three. Standard library only: the venv's start-up hook loads it (from the venv,
where `make setup` copies it) in programs run without any workspace sourced.

Headless windows also write what they show to files in a folder and read key events from a file
there; `owl windows` serves them as a page (http://127.0.0.1:8092/). The folder is
OWL_WINDOWS_DIR; unset, it is the user's own <tmp>/owl-windows-<uid> (made private, 0700), the
one `owl windows` shows by default; set and empty, nothing is written. Nothing happens with a
display.

  <dir>/<program>-<pid>/    one folder per process, made at its first window; removed when the
                            process exits normally. <program> is its script's name without .py
                            (display_camera, keyboard_servos); <pid> tells whether it still runs.
    cv2-<window>.jpg        the latest image given to cv2.imshow(<window>, ...), as the window
                            would show it (8 bit; 16-bit images / 256, float images x 255), JPEG.
                            <window> is the window's name percent-encoded
                            (urllib.parse.quote(name, safe='')): 'camera' -> cv2-camera.jpg.
                            destroyWindow/destroyAllWindows remove it.
    pygame.png              the latest content of the pygame display, at each display.flip() or
                            display.update(), PNG. pygame.display.quit()/pygame.quit() remove it.
    tk-<window>.jpg         the latest frame of a window that a program draws itself and, with no
                            display, writes here through this module's WindowsFolder: turtlesim's
                            'TurtleSim' (tk-TurtleSim.jpg), at its own rate, JPEG. The program
                            reads the keys file with KeyReader.
    keys                    empty when made; append key events to it, one per line:
                                down <key>
                                up <key>
                            <key> is a pygame key name (pygame.key.name()): left, right, up, down,
                            space, return, escape, backspace, tab, a .. z, 0 .. 9, left shift, f1 ...

  Frames: each file is replaced atomically (written as .<name>.tmp beside it, then renamed), so a
  reader never sees a partial image. At most OWL_WINDOWS_FPS (default 10) writes per second per
  window; a frame held back by that limit is written at the program's next imshow, waitKey,
  pollKey, display.flip/update or event call after the interval, so the file ends up showing the
  last image shown.
  Keys: read whenever the program looks for input, each reader in file order from the start:
  - pygame: pygame.event.get/poll/wait/peek/pump first turn new lines into events: `down left`
    posts KEYDOWN (key=K_LEFT, mod, unicode, scancode), `up left` posts KEYUP, and
    pygame.key.get_pressed()[K_LEFT] is True from the event call that posted the down to the one
    that posted the up (get_pressed and get_mods read no lines: as with SDL, the keyboard state
    changes only when events are pumped).
    No key repeat is made: append another `down` for a repeat. A down and its up read in the same
    call arrive as two events in one pygame.event.get(); hold a key for longer than the program's
    input period to have it seen as held.
  - cv2: waitKey/waitKeyEx/pollKey return the next `down` (`up` lines are ignored, as by
    OpenCV) with the code the GUI build's window gives for that key: a character its code
    (a -> 97, space -> 32), return 13, escape 27, backspace 8, tab 9, left/up/right/down
    0xff51/0xff52/0xff53/0xff54 (waitKey returns the low byte: 81/82/83/84), f1 0xffbe ...
    waitKey(delay) returns as soon as a key arrives.
  A line that is not `down <key>`/`up <key>` with a known key is skipped with one line on stderr.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping
    from typing import Any

DEFAULT_FPS = 10.0


def is_number(text: str) -> bool:
    """Whether float() reads the text as a number ('inf' and 'nan' included)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def windows_fps(environ: Mapping[str, str]) -> float:
    """OWL_WINDOWS_FPS if it is a usable rate, else the default."""
    text = environ.get('OWL_WINDOWS_FPS', '')
    fps = float(text) if is_number(text) else DEFAULT_FPS
    return fps if 0 < fps < float('inf') else DEFAULT_FPS


def program_name(argv: list[str]) -> str:
    """The running script's name as the user knows it: display_camera, my_viewer (not my_viewer.py)."""
    name = os.path.basename(argv[0]) if argv and argv[0] not in ('', '-c', '-m') else ''
    if name.endswith('.py'):
        name = name[:-3]
    return name or 'python'




def default_windows_dir() -> str:
    """The user's own folder of headless windows, the one `owl windows` shows by default."""
    import tempfile

    return os.path.join(tempfile.gettempdir(), f'owl-windows-{os.getuid()}')


def windows_root(environ: Mapping[str, str]) -> str | None:
    """Where headless windows are written: OWL_WINDOWS_DIR; unset, the default; empty, nowhere."""
    root = environ.get('OWL_WINDOWS_DIR')
    if root is None:
        return default_windows_dir()
    return root or None


def private_root(root: str) -> None:
    """Make the windows folder's root, only the user's (0700); OSError if it is someone else's.

    Another user could otherwise watch these windows or press their keys.
    """
    os.makedirs(root, mode=0o700, exist_ok=True)
    if os.stat(root).st_uid != os.getuid():
        raise PermissionError(13, 'it belongs to another user')


def window_file(kind: str, name: str) -> str:
    """The seam's file name of a window: pygame.png, or <kind>-<percent-encoded name>.jpg (cv2, tk)."""
    from urllib.parse import quote

    if kind == 'pygame':
        return 'pygame.png'
    return f"{kind}-{quote(name, safe='')}.jpg"


def parse_key_event(line: str) -> tuple[bool, str]:
    """'down left' -> (True, 'left'); 'up left shift' -> (False, 'left shift'); ValueError otherwise."""
    action, _, key = line.strip().partition(' ')
    key = key.strip()
    if action not in ('down', 'up') or not key:
        raise ValueError("expected 'down <key>' or 'up <key>'")
    return action == 'down', key


# What opencv-python's Qt window gives waitKeyEx for a key (measured under Xvfb): characters give
# their code, these named keys their X11 keysym; waitKey returns the low byte.
CV2_NAMED_KEYS: dict[str, int] = {
    'space': 32, 'return': 13, 'escape': 27, 'backspace': 8, 'tab': 9, 'delete': 0xffff,
    'left': 0xff51, 'up': 0xff52, 'right': 0xff53, 'down': 0xff54,
    'home': 0xff50, 'page up': 0xff55, 'page down': 0xff56, 'end': 0xff57, 'insert': 0xff63,
    'left shift': 0xffe1, 'right shift': 0xffe2, 'left ctrl': 0xffe3, 'right ctrl': 0xffe4,
    'caps lock': 0xffe5, 'left alt': 0xffe9, 'right alt': 0xffea,
    **{f'f{n}': 0xffbe + n - 1 for n in range(1, 13)},
}


def cv2_key_code(key: str) -> int | None:
    """WaitKeyEx's value for a pygame key name, None for a key we do not know."""
    if len(key) == 1:
        return ord(key)
    return CV2_NAMED_KEYS.get(key)



def say(line: str) -> None:
    """Print one line on stderr at once: the hook's notices and warnings."""
    print(line, file=sys.stderr, flush=True)


class WindowsFolder:
    """<OWL_WINDOWS_DIR>/<program>-<pid>/: frame files written at a limited rate, the keys file."""

    def __init__(self, root: str, program: str, fps: float) -> None:
        from urllib.parse import quote

        self.root = root
        self.path = os.path.join(root, f"{quote(program, safe='')}-{os.getpid()}")
        self.period = 1.0 / fps
        self.last_write: dict[str, float] = {}
        self.pending: dict[str, Callable[[], bytes]] = {}  # file name -> function returning the encoded bytes
        self.made = False
        self.broken = False

    def make(self) -> bool:
        """The folder and an empty keys file, once; False (said once) if they cannot be made."""
        if self.made or self.broken:
            return self.made
        import atexit

        try:
            private_root(self.root)
            os.makedirs(self.path, exist_ok=True)
            with open(os.path.join(self.path, 'keys'), 'ab'):
                pass
        except OSError as error:
            self.broken = True
            say(f'owl_gui_hook: OWL_WINDOWS_DIR: cannot make {self.path} ({error.strerror}): '
                'windows are not written there')
            return False
        self.made = True
        atexit.register(self.remove)
        return True

    @property
    def keys_path(self) -> str:
        """The keys file, where key events are appended."""
        return os.path.join(self.path, 'keys')

    def show(self, file_name: str, frame: Any, encode: Callable[[Any], bytes],
             copy: Callable[[Any], Any]) -> None:
        """Write encode(frame) now if the rate allows, else keep copy(frame) to write when it does.

        The copy is kept because the program may draw into its frame again before then. The folder is
        made at the first call; nothing is written if it cannot be.
        """
        import time

        if not self.make():
            return
        if time.monotonic() - self.last_write.get(file_name, -1e9) >= self.period:
            self.pending.pop(file_name, None)
            self.write(file_name, lambda: encode(frame))
        else:
            kept = copy(frame)
            self.pending[file_name] = lambda: encode(kept)

    def flush_due(self) -> None:
        """Write the frames held back by the rate limit whose interval is over."""
        import time

        now = time.monotonic()
        for file_name in [f for f in self.pending if now - self.last_write.get(f, -1e9) >= self.period]:
            self.write(file_name, self.pending.pop(file_name))

    def write(self, file_name: str, encode: Callable[[], bytes]) -> None:
        """Replace the file with encode()'s bytes atomically; the first OSError is said, later ones not."""
        import time

        self.last_write[file_name] = time.monotonic()
        final = os.path.join(self.path, file_name)
        temporary = os.path.join(self.path, f'.{file_name}.tmp')
        try:
            with open(temporary, 'wb') as file:
                file.write(encode())
            os.replace(temporary, final)
        except OSError as error:
            if not self.broken:
                self.broken = True
                say(f'owl_gui_hook: OWL_WINDOWS_DIR: cannot write {final} ({error.strerror})')

    def discard(self, file_name: str) -> None:
        """Forget a closed window's file: its frame held back, its last write, the file itself."""
        self.pending.pop(file_name, None)
        self.last_write.pop(file_name, None)
        if self.made:
            try:
                os.remove(os.path.join(self.path, file_name))
            except OSError:
                pass

    def remove(self) -> None:
        """Delete this process's folder with all it holds (make() registers it for the exit)."""
        import shutil

        shutil.rmtree(self.path, ignore_errors=True)
        self.made = False


class KeyReader:
    """New lines of a keys file as (down, key name) events; bad lines are said once and skipped."""

    def __init__(self, path: str, known: Callable[[str], bool]) -> None:
        self.path = path
        self.known = known  # key name -> True if this reader can deliver it
        self.offset = 0
        self.partial = b''
        self.said: set[str] = set()

    def events(self) -> list[tuple[bool, str]]:
        """The events of the lines appended since the last call; [] while the file cannot be read.

        A last line without its newline yet is kept for the next call.
        """
        try:
            size = os.stat(self.path).st_size
        except OSError:
            return []
        if size < self.offset:  # truncated by the writer: start over
            self.offset, self.partial = 0, b''
        if size == self.offset:
            return []
        try:
            with open(self.path, 'rb') as file:
                file.seek(self.offset)
                data = file.read(size - self.offset)
        except OSError:
            return []
        self.offset += len(data)
        *lines, self.partial = (self.partial + data).split(b'\n')
        events = []
        for raw in lines:
            line = raw.decode('utf-8', 'replace').strip()
            if not line:
                continue
            try:
                down, key = parse_key_event(line)
                if not self.known(key):
                    raise ValueError(f'unknown key {key!r}')
            except ValueError as problem:
                if line not in self.said:
                    self.said.add(line)
                    say(f'owl_gui_hook: key event {line!r} in {self.path} skipped: {problem}')
                continue
            events.append((down, key))
        return events
