"""A virtual X display (Xvfb) for tests of real windows, and finding a window on it by name."""

from __future__ import annotations

import os
import re
import select
import shutil
import subprocess
import time

TOOLS = ('Xvfb', 'xwininfo', 'xdotool')


def missing_tool() -> str | None:
    """The first of Xvfb, xwininfo and xdotool that is not installed, or None."""
    return next((tool for tool in TOOLS if shutil.which(tool) is None), None)


class VirtualDisplay:
    """Xvfb on a display number it picks itself (-displayfd), so concurrent tests never collide."""

    def __init__(self, timeout: float = 20.0) -> None:
        read_end, write_end = os.pipe()
        self.server = subprocess.Popen(
            ['Xvfb', '-displayfd', str(write_end), '-screen', '0', '1024x768x24', '-nolisten', 'tcp'],
            pass_fds=(write_end,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL, start_new_session=True)
        os.close(write_end)
        number = b''
        deadline = time.monotonic() + timeout
        try:
            while not number.endswith(b'\n'):
                ready, _, _ = select.select([read_end], [], [], max(0.0, deadline - time.monotonic()))
                chunk = os.read(read_end, 16) if ready else b''
                if not chunk:
                    self.close()
                    raise AssertionError(f'Xvfb gave no display number within {timeout} s')
                number += chunk
        finally:
            os.close(read_end)
        self.display = f':{int(number)}'

    def env(self) -> dict[str, str]:
        """What a process needs to open its windows here (and not on a Wayland session of the host)."""
        return {'DISPLAY': self.display, 'WAYLAND_DISPLAY': '', 'OWL_HEADLESS': ''}

    def windows(self, name: str) -> list[str]:
        """Ids of the windows whose title is exactly name.

        From xwininfo's tree: `xdotool search --name` misses titles that SDL sets as UTF-8 only.
        """
        result = subprocess.run(['xwininfo', '-root', '-tree'], env=dict(os.environ, DISPLAY=self.display),
                                capture_output=True, text=True, timeout=10)
        return [match[1] for match in re.finditer(r'^\s*(0x[0-9a-f]+) "(.*)": ', result.stdout, re.MULTILINE)
                if match[2] == name]

    def wait_for_window(self, name: str, timeout: float = 20.0) -> str:
        deadline = time.monotonic() + timeout
        while not (found := self.windows(name)):
            if time.monotonic() > deadline:
                raise AssertionError(f"no window named {name!r} on {self.display} within {timeout} s")
            time.sleep(0.1)
        return found[0]

    def key(self, window: str, *keys: str) -> None:
        """Type keys (X keysym names: Left, a, Escape) into a window, as a user at the keyboard."""
        env = dict(os.environ, DISPLAY=self.display)
        subprocess.run(['xdotool', 'windowfocus', '--sync', window], env=env, check=True, timeout=10)
        subprocess.run(['xdotool', 'key', '--delay', '50', *keys], env=env, check=True, timeout=10)

    def close(self) -> None:
        if self.server.poll() is None:
            self.server.terminate()
            try:
                self.server.wait(5)
            except subprocess.TimeoutExpired:
                self.server.kill()
                self.server.wait(5)
