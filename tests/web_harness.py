"""The system tests' view of our browser pages: Chromium driven by Playwright, PageSocket and Rqt.

Debian's Chromium driven by Playwright (the `browser` and `page` fixtures of conftest.py),
PageSocket, a page's WebSocket from Python for what a browser never sends (malformed JSON, oversized
messages), and Rqt, a running `rqt` with its JSON API.

Playwright never downloads a browser here: it launches Debian's Chromium headless shell (`apt-get
install chromium-headless-shell`; scripts/test_prereqs.sh installs it when `make test` runs as root).
"""

from __future__ import annotations

import asyncio
import json
import os
import re
import socket
import threading
import urllib.error
import urllib.request
from pathlib import Path
from typing import TYPE_CHECKING, Any

import aiohttp
from owl_web.codec import unpack_frame
from ros_harness import wait_until

if TYPE_CHECKING:
    from playwright.sync_api import ViewportSize

# Chromium's own headless build (the same Blink, V8 and SwiftShader WebGL as the browser, without the
# browser's windowing layer): against the full browser's headless mode, it starts in a fifth of the
# CPU (0.35 s against 1.6-2.0 s) and spends about 45 % less on an rqt or module page test.
CHROMIUM = Path('/usr/lib/chromium/chromium-headless-shell')
# The public name of a class server in the tests (tests/prefix_proxy.py): Chromium finds it at 127.0.0.1,
# so the pages see a Host and an Origin that are not this machine's, as behind a real one.
PROXY_HOST = 'hub.owl.test'
# Root needs --no-sandbox; the rest keeps Chromium from reaching out to the network or updating.
CHROMIUM_ARGS = ['--no-sandbox', '--disable-gpu', '--disable-background-networking',
                 '--disable-component-update', '--no-first-run', '--disable-default-apps',
                 '--disable-sync', '--metrics-recording-only',
                 f'--host-resolver-rules=MAP {PROXY_HOST} 127.0.0.1']
VIEWPORT: ViewportSize = {'width': 1280, 'height': 800}
SCREENSHOTS = Path(__file__).resolve().parents[1] / 'docs' / 'screenshots'
# What Chromium logs while a page's server is away (a module restarting or rebooting, robot_view
# stopped): the page's WebSocket reconnecting and a fetch meeting a closed port.
SERVER_AWAY = re.compile(r'ERR_CONNECTION_REFUSED|WebSocket connection to .* failed')
RQT_URL_LINE = r'^rqt: open (http://127\.0\.0\.1:\d+/)(#[a-z-]+)? in a browser \(Ctrl-C to quit\)$'


def chromium_missing() -> str | None:
    """Why the browser tests cannot run here, in one line, or None."""
    if not CHROMIUM.exists():
        return f"{CHROMIUM} not found (browser tests skip): 'sudo apt-get install chromium-headless-shell'"
    return None


class Browser:
    """One headless Chromium (conftest.py starts one per test module)."""

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
    """A Playwright page (its methods are this object's) that keeps console errors and uncaught exceptions.

    conftest.py fails the test that leaves any.
    """

    def __init__(self, page: Any) -> None:
        self.page = page
        self.console_errors: list[str] = []
        self.requested: list[str] = []  # every URL the page loaded or fetched
        page.on('request', lambda request: self.requested.append(request.url))
        page.on('console', self._on_console)
        page.on('pageerror', lambda error: self.console_errors.append(f'uncaught: {error}'))

    def _on_console(self, message: Any) -> None:
        if message.type == 'error':
            self.console_errors.append(
                message.text + (f" ({message.location['url']})" if message.location.get('url') else ''))

    def __getattr__(self, name: str) -> Any:
        return getattr(self.page, name)

    def forgive_server_away(self) -> None:
        """Drop the console errors of the page's server being away (see SERVER_AWAY); any other stays."""
        self.console_errors[:] = [error for error in self.console_errors if not SERVER_AWAY.search(error)]

    def screenshot_at_390(self, name: str, showing: str) -> Path:
        """docs/screenshots/<name>_390.png: the page as a 390 px phone shows it, scrolled to `showing`.

        The viewport goes back to VIEWPORT afterwards.
        """
        self.page.set_viewport_size({'width': 390, 'height': 844})
        try:
            self.page.locator(showing).scroll_into_view_if_needed()
            return self.screenshot_to(f'{name}_390')
        finally:
            self.page.set_viewport_size(VIEWPORT)

    def screenshot_to(self, name: str, full_page: bool = False) -> Path:
        """A screenshot for the documentation: docs/screenshots/<name>.png.

        The whole page with full_page, else the viewport. A picture that hardly differs from the one there
        (a live page is never the same twice: the camera's clock, the plots' noise) leaves the file as it
        is, so a test run does not dirty the tree when the page did not change; OWL_SCREENSHOTS=always
        writes it anyway (after a change too small for that test, say).
        """
        return keep_screenshot(name, self.page.screenshot(full_page=full_page))


def keep_screenshot(name: str, picture: bytes) -> Path:
    """Write docs/screenshots/<name>.png of a PNG picture unless the one there hardly differs."""
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    path = SCREENSHOTS / f'{name}.png'
    if os.environ.get('OWL_SCREENSHOTS') == 'always' or not path.exists() \
            or not nearly_the_same(path.read_bytes(), picture):
        path.write_bytes(picture)
    return path


# The share of pixels that may differ visibly in "the same" picture: two runs of robot_view.png (the
# head following the IMU, the camera) differ in 1.9 %, of robot_view_plots.png in 0.4 %; a change
# as small as a plot's axis labels (0.8 %) needs OWL_SCREENSHOTS=always.
SAME_PICTURE_PIXELS = 0.03
VISIBLE_DIFFERENCE = 48  # of 255 in any colour channel


def nearly_the_same(old_png: bytes, new_png: bytes) -> bool:
    """Whether two screenshots show the same page.

    They do when they have the same size and at most SAME_PICTURE_PIXELS of their pixels differ by more
    than VISIBLE_DIFFERENCE.
    """
    import cv2  # here: only a test that takes a picture needs OpenCV loaded
    import numpy
    old, new = (cv2.imdecode(numpy.frombuffer(png, numpy.uint8), cv2.IMREAD_COLOR)
                for png in (old_png, new_png))
    if old is None or new is None or old.shape != new.shape:
        return False
    differing = (cv2.absdiff(old, new).max(axis=2) > VISIBLE_DIFFERENCE).mean()
    return bool(differing <= SAME_PICTURE_PIXELS)


class SocketClosed(Exception):
    """The server closed the WebSocket; .code is the close code."""

    def __init__(self, code: int | None) -> None:
        super().__init__(f'WebSocket closed with code {code}')
        self.code = code


class PageSocket:
    """A page's WebSocket (/ws of an owl_web server) from a test, through aiohttp's client.

    The client runs on an event loop of its own thread.
    """

    def __init__(self, base_url: str) -> None:
        self._loop = asyncio.new_event_loop()
        self._thread = threading.Thread(target=self._loop.run_forever, name='page socket', daemon=True)
        self._thread.start()
        self._session, self._websocket = self._run(self._connect(base_url.rstrip('/') + '/ws'))

    def _run(self, coroutine: Any, timeout: float = 15.0) -> Any:
        return asyncio.run_coroutine_threadsafe(coroutine, self._loop).result(timeout)

    @staticmethod
    async def _connect(url: str) -> tuple[aiohttp.ClientSession, aiohttp.ClientWebSocketResponse[bool]]:
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

    def close_code_after(self, text: str) -> int | None:
        """Send text and read until the server closes: its close code, or None if the send itself failed.

        A server that closes on a message over its limit may reset the connection while the client
        is still writing it: aiohttp's send then fails with "Connection lost".
        """
        try:
            self.send(text)
        except ConnectionError:
            return None
        while True:
            try:
                self.receive()
            except SocketClosed as closed:
                return closed.code

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


def open_from_index(page: BrowserPage, base: str, mount: str) -> None:
    """Go to the index at base and click the link of the page at mount."""
    page.goto(base)
    page.wait_for_selector(f'li.running[data-mount="{mount}"] a', timeout=20_000)
    page.click(f'li.running[data-mount="{mount}"] a')
    page.wait_for_url(f'{base}{mount}/**', timeout=10_000)


def check_module_pages(page: BrowserPage, base: str) -> None:
    """A module's System Status, live; the IMU's Debug GUI, live."""
    open_from_index(page, base, 'servo-pan')
    page.wait_for_function('() => window.modulePage.device !== null && window.modulePage.samples.length >= 2',
                           timeout=20_000)
    assert page.evaluate('window.modulePage.device.network.address') == '10.42.0.8'
    assert page.inner_text('#connection') == 'connected'
    open_from_index(page, base, 'imu-x1684267976913')
    page.click('#menu-debug')
    page.wait_for_function('() => window.modulePage.viewReady && window.modulePage.orientation',
                           timeout=20_000)
    assert page.text_content('#roll').endswith('°')


# A JS function for page.evaluate's scripts: on_kit_state(view, seen) calls seen(imu) at every kit
# state the robot view's page takes (each one sets window.robotView.imu), the value kept as before.
ON_KIT_STATE = """(view, seen) => {
  let imu = view.imu;
  Object.defineProperty(view, 'imu', {
    configurable: true,
    get: () => imu,
    set: (value) => { imu = value; seen(value); },
  });
}"""


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return probe.getsockname()[1]


def http(method: str, url: str, body: Any = None) -> tuple[int, dict[str, str], bytes]:
    """(status, headers, body) of one request; a dict body goes as JSON, bytes as they are."""
    data = body if isinstance(body, bytes) or body is None else json.dumps(body).encode()
    request = urllib.request.Request(url, data=data, method=method)
    if data is not None:
        request.add_header('Content-Type', 'application/json')
    try:
        with urllib.request.urlopen(request, timeout=30) as response:
            return response.status, dict(response.headers), response.read()
    except urllib.error.HTTPError as error:
        return error.code, dict(error.headers), error.read()


class Rqt:
    """A running `rqt --no-browser` and its JSON API."""

    def __init__(self, ros: Any, *argv: str) -> None:
        self.process = ros.command(argv or ['rqt', '--port', str(free_port()), '--no-browser'])
        self.base, self.fragment = self.process.wait_for(RQT_URL_LINE, timeout=30)[0].groups()

    def call(self, method: str, path: str, body: Any = None) -> tuple[int, Any]:
        status, _, data = http(method, self.base + path.lstrip('/'), body)
        return status, json.loads(data)

    def ok(self, method: str, path: str, body: Any = None, status: int = 200) -> Any:
        got, data = self.call(method, path, body)
        assert got == status, data
        return data

    def refused(self, status: int, method: str, path: str, body: Any = None) -> str:
        """The error line of a refused request; the server must still answer afterwards."""
        got, data = self.call(method, path, body)
        assert got == status, data
        assert list(data) == ['error'], data
        assert '\n' not in data['error'], data
        assert data['error'], data
        assert self.call('GET', '/api/topics')[0] == 200
        return data['error']

    def wait_for(self, condition: Any, what: str, timeout: float = 20.0) -> None:
        wait_until(condition, timeout, what)

    def socket(self) -> PageSocket:
        """The page's WebSocket, as the page opens it."""
        return PageSocket(self.base)

    def stop_cleanly(self) -> None:
        assert self.process.stop() == 0, self.process.output
        assert 'Traceback' not in self.process.output
