"""The system tests' view of our browser pages: Debian's Chromium driven by Playwright (the `browser`
and `page` fixtures of conftest.py), and PageSocket, a page's WebSocket from Python for what a
browser never sends (malformed JSON, oversized messages).

Playwright never downloads a browser here: it launches /usr/bin/chromium (`apt-get install
chromium`; scripts/test_prereqs.sh installs it when `make test` runs as root).
"""

from __future__ import annotations

import asyncio
import json
import threading
from pathlib import Path
from typing import Any

import aiohttp
from owl_web.codec import unpack_frame

CHROMIUM = Path('/usr/bin/chromium')
# Root needs --no-sandbox; the rest keeps Chromium from reaching out to the network or updating.
CHROMIUM_ARGS = ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
                 '--disable-component-update', '--no-first-run', '--disable-default-apps',
                 '--disable-sync', '--metrics-recording-only']
VIEWPORT = {'width': 1280, 'height': 800}
SCREENSHOTS = Path(__file__).resolve().parents[1] / 'docs' / 'screenshots'


def chromium_missing() -> str | None:
    """Why the browser tests cannot run here, in one line, or None."""
    if not CHROMIUM.exists():
        return f"{CHROMIUM} not found (the browser tests skip): 'sudo apt-get install chromium'"
    return None


class Browser:
    """One headless Chromium for a whole test session."""

    def __init__(self) -> None:
        from playwright.sync_api import sync_playwright
        self._playwright = sync_playwright().start()
        try:
            self.chromium = self._playwright.chromium.launch(
                executable_path=str(CHROMIUM), args=CHROMIUM_ARGS, headless=True)
        except BaseException:
            self._playwright.stop()
            raise

    def new_page(self) -> BrowserPage:
        return BrowserPage(self.chromium.new_page(viewport=VIEWPORT))

    def close(self) -> None:
        self.chromium.close()
        self._playwright.stop()


class BrowserPage:
    """A Playwright page (its methods are this object's) that keeps every console error and
    uncaught exception; conftest.py fails the test that leaves any."""

    def __init__(self, page: Any) -> None:
        self.page = page
        self.console_errors: list[str] = []
        page.on('console', lambda message: message.type == 'error' and self.console_errors.append(
            f'{message.text} ({message.location.get("url", "")})'))
        page.on('pageerror', lambda error: self.console_errors.append(f'uncaught: {error}'))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.page, name)

    def screenshot_to(self, name: str) -> Path:
        """A screenshot for the documentation: docs/screenshots/<name>.png."""
        SCREENSHOTS.mkdir(parents=True, exist_ok=True)
        path = SCREENSHOTS / f'{name}.png'
        self.page.screenshot(path=str(path))
        return path


class SocketClosed(Exception):
    """The server closed the WebSocket; .code is the close code."""

    def __init__(self, code: int | None) -> None:
        super().__init__(f'WebSocket closed with code {code}')
        self.code = code


class PageSocket:
    """A page's WebSocket (/ws of an owl_web server) from a test, through aiohttp's client on an
    event loop of its own thread."""

    def __init__(self, base_url: str) -> None:
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name='page socket', daemon=True)
        self._thread.start()
        self._session, self._websocket = self._run(self._connect(base_url.rstrip('/') + '/ws'))

    def _run(self, coroutine: Any, timeout: float = 15.0) -> Any:
        return asyncio.run_coroutine_threadsafe(coroutine, self._loop).result(timeout)

    @staticmethod
    async def _connect(url: str) -> tuple[aiohttp.ClientSession, aiohttp.ClientWebSocketResponse]:
        session = aiohttp.ClientSession()
        return session, await session.ws_connect(url, max_msg_size=16 << 20)

    def send(self, message: dict[str, Any] | str | bytes) -> None:
        """A dict goes as JSON text, a str as it is (malformed JSON too), bytes as a binary message."""
        if isinstance(message, bytes):
            self._run(self._websocket.send_bytes(message))
        else:
            self._run(self._websocket.send_str(message if isinstance(message, str) else json.dumps(message)))

    def receive(self, timeout: float = 10.0) -> dict[str, Any]:
        """The next message; a binary frame's payload is under the key 'payload' of its header."""
        message = self._run(self._websocket.receive(timeout), timeout + 5)
        if message.type == aiohttp.WSMsgType.TEXT:
            return json.loads(message.data)
        if message.type == aiohttp.WSMsgType.BINARY:
            header, payload = unpack_frame(message.data)
            return {**header, 'payload': payload}
        raise SocketClosed(self._websocket.close_code)

    def receive_matching(self, wanted: Any, what: str, timeout: float = 15.0) -> dict[str, Any]:
        """The first message for which wanted(message) is true, skipping others."""
        loop_time = self._loop.time
        deadline = loop_time() + timeout
        while True:
            left = deadline - loop_time()
            if left <= 0:
                raise AssertionError(f'timed out after {timeout} s waiting for {what}')
            try:
                message = self.receive(left)
            except (asyncio.TimeoutError, TimeoutError):
                continue
            if wanted(message):
                return message

    def subscribe(self, subscription_id: int | str, channel: str, **params: Any) -> None:
        self.send({'type': 'subscribe', 'id': subscription_id, 'channel': channel, **params})

    def __enter__(self) -> PageSocket:
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()

    def close(self) -> None:
        try:
            self._run(self._websocket.close(), 5)
            self._run(self._session.close(), 5)
        finally:
            self._loop.call_soon_threadsafe(self._loop.stop)
            self._thread.join(5)
