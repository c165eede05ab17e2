"""`owl windows`: the headless windows of this user's programs on one local page, live, with their keys.

A thread looks at the windows' folder every POLL_PERIOD (the hook writes at most 10 frames/s per
window by default, turtlesim about 33 while something moves) and pushes over owl_web's WebSocket:
the list of windows when it changes (channel `windows`), each watched window's frame when its file
changes (channel `window`, parameter `window`: the id from the list), and a key pressed on the page
goes to that program's keys file (command `key`).
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from owl_web.codec import ApiError, check_keys
from owl_web.server import Subscription, WebServer

from owl_cli.windows.folder import Window, append_key_event, read_frame, scan

POLL_PERIOD = 0.015  # s: under turtlesim's 30 ms between frames, so none waits long
STATIC_DIR = Path(__file__).parent / 'static'


class WindowsPage:
    """The page's channels and command on a WebServer, and the thread that watches the folder."""

    def __init__(self, server: WebServer, root: Path) -> None:
        self.root = root
        self._lock = threading.Lock()
        self._windows: dict[str, Window] = {}
        self._list_watchers: set[Subscription] = set()
        self._frame_watchers: dict[Subscription, int] = {}  # -> the mtime of the frame last sent
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._watch_folder, name='owl-windows', daemon=True)
        server.channel('windows', self._open_list, self._list_watchers.discard)
        server.channel('window', self._open_window, self._close_window)
        server.command('key', self._key)

    def start(self) -> None:
        """Look at the folder once, then start the thread that watches it every POLL_PERIOD s."""
        self._look()
        self._thread.start()

    def stop(self) -> None:
        """Stop the watching thread (waiting up to 2 s for it)."""
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=2)

    def _summaries(self) -> dict[str, Any]:
        return {'folder': str(self.root), 'windows': [w.summary() for w in self._windows.values()]}

    def _open_list(self, watcher: Subscription) -> None:
        check_keys(watcher.params, ())
        with self._lock:
            self._list_watchers.add(watcher)
            summaries = self._summaries()
        watcher.send(summaries)

    def _window(self, arguments: dict[str, Any]) -> Window:
        name = arguments.get('window')
        if not isinstance(name, str):
            raise ApiError(400, "'window' must be a window's id from the list (a string)")
        with self._lock:
            window = self._windows.get(name)
            known = list(self._windows)
        if window is None:
            raise ApiError(404, f"no window '{name[:100]}'; open now: {', '.join(known) or 'none'}")
        return window

    def _open_window(self, watcher: Subscription) -> None:
        check_keys(watcher.params, ('window',), ('window',))
        self._window(watcher.params)
        with self._lock:
            self._frame_watchers[watcher] = 0  # its first look sends the current frame

    def _close_window(self, watcher: Subscription) -> None:
        with self._lock:
            self._frame_watchers.pop(watcher, None)

    def _key(self, arguments: dict[str, Any]) -> None:
        check_keys(arguments, ('window', 'event', 'key'), ('window', 'event', 'key'))
        window = self._window(arguments)
        try:
            append_key_event(window, arguments['event'], arguments['key'])
        except ValueError as problem:
            raise ApiError(400, str(problem)) from None
        except OSError as error:
            raise ApiError(404, f'{window.program} ({window.pid}) has closed its windows: '
                                f'{error.strerror}') from None

    def _watch_folder(self) -> None:
        while not self._stop.wait(POLL_PERIOD):
            self._look()

    def _look(self) -> None:
        windows = {w.id: w for w in scan(self.root)}
        with self._lock:
            listed = [w.summary() for w in windows.values()] != [w.summary() for w in self._windows.values()]
            self._windows = windows
            summaries = self._summaries()
            list_watchers = list(self._list_watchers)
            due = [(watcher, windows.get(watcher.params['window']), sent)
                   for watcher, sent in self._frame_watchers.items()]
        if listed:
            for watcher in list_watchers:
                watcher.send(summaries)
        for watcher, window, sent in due:
            if window is None:
                if sent >= 0:
                    watcher.send({'closed': True})
                    with self._lock:
                        if watcher in self._frame_watchers:
                            self._frame_watchers[watcher] = -1
                continue
            if window.changed == sent:
                continue
            frame = read_frame(window)
            if frame is None:
                continue
            with self._lock:
                if watcher not in self._frame_watchers:
                    continue
                self._frame_watchers[watcher] = window.changed
            watcher.send_binary({'window': window.id, 'content_type': window.content_type}, frame)
