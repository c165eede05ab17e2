"""A virtual X display for the window tests: Xvfb, and xdotool to find windows and press keys.

The `x_display` fixture (conftest.py) starts one Xvfb for the whole session; a test that needs a
real window runs its process with DISPLAY set to it. Without Xvfb or xdotool the tests skip with
one line (scripts/test_prereqs.sh installs them when run as root).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import re
import select
import shutil
import subprocess
import tempfile
import time

from gates import prerequisite_missing

# A window in `xwininfo -root -tree`: its id and its title.
WINDOW_LINE = re.compile(r'^\s*(0x[0-9a-f]+) "(.*)":', re.MULTILINE)
# Environment entries (None removes one) for a process with no display at all, as on a server or
# in a container, and none of the window hook's settings (owl_venv_hooks/owl_gui_hook.py) from the
# shell.
NO_DISPLAY = {'DISPLAY': None, 'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': None, 'OWL_WINDOWS_DIR': None,
              'OWL_WINDOWS_FPS': None}
# With VirtualDisplay.env(): real windows, also when the shell has a Wayland session or OWL_HEADLESS.
REAL_WINDOWS = {'WAYLAND_DISPLAY': None, 'OWL_HEADLESS': None}
MISSING = "{program} is not installed, so this window test is skipped ('sudo apt-get install {package}')"


def require(program: str, package: str) -> None:
    if shutil.which(program) is None:
        prerequisite_missing(MISSING.format(program=program, package=package))


def read_line(fd: int, timeout: float) -> str:
    """Text from fd up to its first newline (or EOF, or the timeout), stripped.

    Xvfb writes its display number and the newline in two writes and exits ("Cannot write display
    number to fd") when the second one finds the pipe closed: read until the newline.
    """
    text = b''
    deadline = time.monotonic() + timeout
    while not text.endswith(b'\n'):
        ready, _, _ = select.select([fd], [], [], max(0.0, deadline - time.monotonic()))
        chunk = os.read(fd, 64) if ready else b''
        if not chunk:
            break
        text += chunk
    return text.decode().strip()


class VirtualDisplay:
    """An Xvfb server on a display number it picks itself (-displayfd), stopped by close()."""

    def __init__(self, timeout: float = 10.0) -> None:
        require('Xvfb', 'xvfb')
        require('xdotool', 'xdotool')
        require('xwininfo', 'x11-utils')
        read_end, write_end = os.pipe()
        # Xvfb's own lines (a refused client, a fatal error) for a failure message: see state().
        self.log = tempfile.TemporaryFile()
        # -noreset: by default an X server resets when its last client leaves (here each xwininfo
        # poll), and a window that connects during the reset is refused ("could not connect to
        # display"): 4 of 140 cv2 window starts beside a polling loop, 0 of 140 with -noreset.
        self.process = subprocess.Popen(
            ['Xvfb', '-displayfd', str(write_end), '-screen', '0', '1280x1024x24', '-nolisten', 'tcp',
             '-noreset'],
            pass_fds=(write_end,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=self.log)
        os.close(write_end)
        try:
            number = read_line(read_end, timeout)
        finally:
            os.close(read_end)
        if not number.isdigit():
            self.close()
            raise RuntimeError(f'Xvfb did not report its display within {timeout} s')
        self.name = f':{number}'

    def env(self) -> dict[str, str]:
        """Environment entries that put a process on this display."""
        return {'DISPLAY': self.name}

    def xdotool(self, *args: str, timeout: float = 10.0) -> str:
        result = subprocess.run(['xdotool', *args], capture_output=True, text=True, timeout=timeout,
                                env=dict(os.environ, DISPLAY=self.name), check=False)
        return result.stdout

    def windows(self, name: str | None = None, pid: int | None = None) -> list[str]:
        """Ids of the windows whose title matches the regex name, or that the process pid owns."""
        if pid is not None:
            return self.xdotool('search', '--pid', str(pid)).split()
        # xdotool 3.2016's --name misses SDL's windows; xwininfo lists every title it has.
        result = subprocess.run(['xwininfo', '-root', '-tree'], capture_output=True, text=True, timeout=10,
                                env=dict(os.environ, DISPLAY=self.name), check=False)
        pattern = re.compile(name or '.')
        return [match.group(1) for match in WINDOW_LINE.finditer(result.stdout)
                if pattern.search(match.group(2))]

    def wait_for_window(self, name: str | None = None, pid: int | None = None,
                        timeout: float = 20.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            found = self.windows(name, pid)
            if found:
                return found[0]
            time.sleep(0.2)
        raise AssertionError(f'no window (name {name!r}, pid {pid}) on {self.name} within {timeout} s; '
                             f'{self.state()}')

    def state(self) -> str:
        """Whether Xvfb runs and answers, and the last lines it wrote.

        A failed window test needs them to tell a display problem from a program that opened no window.
        """
        code = self.process.poll()
        running = 'Xvfb is running' if code is None else f'Xvfb exited with code {code}'
        probe = subprocess.run(['xwininfo', '-root'], capture_output=True, text=True, timeout=10,
                               env=dict(os.environ, DISPLAY=self.name), check=False)
        answers = 'answers' if probe.returncode == 0 else f'does not answer ({probe.stderr.strip()})'
        self.log.seek(0)
        lines = self.log.read().decode(errors='replace').strip().splitlines()[-10:]
        return f'{running} and {answers}; its last lines: ' + ('\n'.join(lines) or '(none)')

    def press(self, window: str, key: str, seconds: float) -> None:
        """Hold an X key (e.g. 'Left') in a window for the given time, as a keyboard does.

        XTEST to the focused window; Xvfb has no window manager to give the focus, so it is set first.
        """
        self.xdotool('windowfocus', '--sync', window)
        self.xdotool('keydown', key)
        time.sleep(seconds)
        self.xdotool('keyup', key)

    def type(self, window: str, *keys: str) -> None:
        """Type X keys (Left, a, Escape) into a window as a keyboard does.

        XTEST, not XSendEvent, which Qt ignores; the window gets the focus first (Xvfb has no window
        manager).
        """
        self.xdotool('windowfocus', '--sync', window)
        self.xdotool('key', '--delay', '50', *keys)

    def close_window(self, window: str) -> None:
        """Ask a window to close as a window manager's close button does (WM_DELETE_WINDOW)."""
        send_close_request(self.name, int(window, 0))

    def close(self) -> None:
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(5)
            except subprocess.TimeoutExpired:
                self.process.kill()
        self.log.close()


class ClientMessage(ctypes.Structure):
    """Xlib's XClientMessageEvent with 32-bit data (X11/Xlib.h)."""

    _fields_ = [('type', ctypes.c_int), ('serial', ctypes.c_ulong), ('send_event', ctypes.c_int),
                ('display', ctypes.c_void_p), ('window', ctypes.c_ulong), ('message_type', ctypes.c_ulong),
                ('format', ctypes.c_int), ('data', ctypes.c_long * 5)]


class XEvent(ctypes.Union):
    _fields_ = [('client_message', ClientMessage), ('pad', ctypes.c_long * 24)]


X_CLIENT_MESSAGE = 33  # ClientMessage in X11/X.h


def send_close_request(display_name: str, window: int) -> None:
    """Send a window the WM_PROTOCOLS/WM_DELETE_WINDOW message, as a click on its close button does.

    A window manager sends it when the close button is clicked; xdotool 3.2016 can only destroy a window
    or kill its client.
    """
    library = ctypes.util.find_library('X11')
    if library is None:
        prerequisite_missing(MISSING.format(program='libX11', package='libx11-6'))
    xlib = ctypes.CDLL(library)
    xlib.XOpenDisplay.restype = ctypes.c_void_p
    xlib.XOpenDisplay.argtypes = [ctypes.c_char_p]
    xlib.XInternAtom.restype = ctypes.c_ulong
    xlib.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    xlib.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long,
                                ctypes.POINTER(XEvent)]
    xlib.XFlush.argtypes = xlib.XCloseDisplay.argtypes = [ctypes.c_void_p]
    display = xlib.XOpenDisplay(display_name.encode())
    if not display:
        raise AssertionError(f'cannot open X display {display_name}')
    try:
        event = XEvent()
        message = event.client_message
        message.type = X_CLIENT_MESSAGE
        message.window = window
        message.message_type = xlib.XInternAtom(display, b'WM_PROTOCOLS', 0)
        message.format = 32
        message.data[0] = xlib.XInternAtom(display, b'WM_DELETE_WINDOW', 0)
        message.data[1] = 0  # CurrentTime
        if not xlib.XSendEvent(display, window, 0, 0, ctypes.byref(event)):
            raise AssertionError(f'XSendEvent to window {window:#x} failed')
        xlib.XFlush(display)
    finally:
        xlib.XCloseDisplay(display)
