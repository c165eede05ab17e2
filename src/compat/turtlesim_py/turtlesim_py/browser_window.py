"""The TurtleSim window without a display: its frames and keys go through the windows folder.

Where no display can be used, turtlesim_node writes what its window would show to
<windows folder>/turtlesim_node-<pid>/tk-TurtleSim.jpg (owl_windows.folder, the seam that OpenCV's
and pygame's headless windows use too), and `owl windows` shows it in a browser, live. Keys pressed
on that page come back through the folder's keys file; held arrow keys drive turtle1 as
turtle_teleop_key's do.
"""

from __future__ import annotations

import io
import os
import sys

from owl_windows.folder import KeyReader, WindowsFolder, program_name, window_file, windows_root
from PIL import Image

FILE_NAME = window_file('tk', 'TurtleSim')
JPEG_QUALITY = 95  # trails stay crisp; 1-3 ms a frame, where PNG took about 10 ms
FOLDER_FPS = 60.0  # the node already paces its frames (WINDOW_PERIOD); the folder must not hold them back


def encode_jpeg(frame: Image.Image) -> bytes:
    """The frame as the seam's JPEG bytes."""
    buffer = io.BytesIO()
    frame.save(buffer, format='JPEG', quality=JPEG_QUALITY)
    return buffer.getvalue()


class BrowserWindow:
    """The TurtleSim window as a file of the windows folder, and the keys held down on its page."""

    def __init__(self, folder: WindowsFolder, reader: KeyReader) -> None:
        self._folder = folder
        self._reader = reader
        self._held: set[str] = set()

    @classmethod
    def open(cls) -> BrowserWindow | None:
        """The window in this user's windows folder; None without a usable folder.

        OWL_WINDOWS_DIR chooses the folder as for every headless window; set and empty, there is none.
        A folder that cannot be made is said in one line on stderr.
        """
        root = windows_root(dict(os.environ))
        if root is None:
            return None
        folder = WindowsFolder(root, program_name(sys.argv), FOLDER_FPS)
        if not folder.make():
            return None
        return cls(folder, KeyReader(folder.keys_path, known=lambda key: True))

    @property
    def path(self) -> str:
        """The process's folder, where the frame file and the keys file are."""
        return self._folder.path

    def show(self, frame: Image.Image) -> None:
        """Write the frame for the page (replacing the file atomically)."""
        self._folder.show(FILE_NAME, frame, encode_jpeg, Image.Image.copy)

    def pump(self) -> None:
        """Read the key events pressed on the page since the last call."""
        for down, key in self._reader.events():
            if down:
                self._held.add(key)
            else:
                self._held.discard(key)

    def held_keys(self) -> frozenset[str]:
        """The keys held down on the page now (pygame's names: left, up, ...)."""
        return frozenset(self._held)

    def close(self) -> None:
        """Remove the process's folder: the window leaves the page."""
        self._folder.remove()
