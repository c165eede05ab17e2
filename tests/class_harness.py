"""The class server's harness: `owl class serve` for a class of new accounts, its visitors, terminals.

The system tests (tests/test_class_server.py) and the class bench (bench/class_server.py) share it.
Every account a Hub makes is removed by close().
"""

from __future__ import annotations

import asyncio
import hashlib
import http.client
import http.cookiejar
import json
import os
import re
import secrets
import shutil
import ssl
import subprocess
import sys
import tempfile
import urllib.parse
import urllib.request
from collections.abc import Coroutine
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

import aiohttp
from owl_cli.classroom.worlds import front_door_port, read_domains
from owl_common.processes import RosProcess, dies_with_this_process
from ros_harness import wait_until
from web_harness import free_port

START_TIMEOUT = 300.0  # s: the first start installs JupyterHub and builds the students' lab
# One lab for every hub started from this checkout (the tests' and the bench's, in any worker): built
# once, and again only when a file of the checkout changed.
CHECKOUT = Path(__file__).resolve().parents[1]
LAB = Path(tempfile.gettempdir()) / f'owl-class-lab-{hashlib.sha256(bytes(CHECKOUT)).hexdigest()[:8]}'
Result = TypeVar('Result')
# The lab's build as `owl class serve` makes it (ensure_lab, the same Python, so the same stamp).
LAB_BUILD = [sys.executable, '-c',
             'import sys; from pathlib import Path; from owl_cli.classroom.hub import SYSTEM_PYTHON; '
             'from owl_cli.classroom.lab import ensure_lab; ensure_lab(Path(sys.argv[1]), Path(sys.argv[2]), '
             'SYSTEM_PYTHON)', str(LAB), str(CHECKOUT)]


def wait_for_lab() -> None:
    """Return once the lab is built: by a build started earlier (its lock is waited for) or by this one.

    A build that fails here is left to the hub's own start, which says why in its one line.
    """
    subprocess.run(LAB_BUILD, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False,
                   preexec_fn=dies_with_this_process())


TEACHER_PASSWORD = 'teacher-secret-1'


def new_name() -> str:
    return f'owl{secrets.token_hex(3)}'


@dataclass
class Hub:
    """`owl class serve` for a class of students and a teacher, in a folder of its own (state, class list)."""

    folder: Path
    port: int
    teacher: str
    students: dict[str, str]  # name -> password
    process: RosProcess | None = None
    fingerprint: str = ''
    made: set[str] = field(default_factory=set)

    def write_list(self) -> Path:
        path = self.folder / 'class.txt'
        path.write_text(''.join(f'{name} {password}\n' for name, password in self.students.items()))
        return path

    def command(self, class_list: Path) -> RosProcess:
        env = {**os.environ, 'OWL_CLASS_TEACHER_PASSWORD': TEACHER_PASSWORD}
        return RosProcess(['owl', 'class', 'serve', '--students', str(class_list), '--teacher', self.teacher,
                           '--port', str(self.port), '--state', str(self.folder / 'state'),
                           '--lab', str(LAB)], env, label='owl class serve')

    def start(self) -> None:
        self.made |= {*self.students, self.teacher}
        self.process = self.command(self.write_list())
        line = self.process.wait_for(r'certificate SHA-256 ([0-9A-F:]+)\)', START_TIMEOUT)[0]
        self.fingerprint = line.group(1)
        wait_until(lambda: answers(self.port), 30, 'the hub answering')

    def front_door(self, name: str) -> str:
        """The student's front door on this machine (their account's own port, owl_cli.classroom.worlds)."""
        return f'http://127.0.0.1:{front_door_port(read_domains(self.folder / "state")[name])}/'

    def stop(self) -> int:
        assert self.process is not None
        return self.process.stop(timeout=20)

    @classmethod
    def open(cls, students: int) -> Hub:
        """A hub for that many new students and a new teacher, started (close() it)."""
        # Not under pytest's own folder, which only root may pass through: every student runs the lab inside.
        folder = Path(tempfile.mkdtemp(prefix='owl-class-test-'))
        folder.chmod(0o711)
        names = {new_name(): f'pw-{secrets.token_hex(4)}' for _ in range(students)}
        hub = cls(folder, free_port(), new_name(), names)
        try:
            hub.start()
        except BaseException:
            hub.close()
            raise
        return hub

    def close(self) -> int | None:
        """Ctrl-C for the class server (its exit code; None if it never ran); no account or file is left."""
        try:
            return self.stop() if self.process is not None else None
        finally:
            remove_accounts(self.made)
            shutil.rmtree(self.folder, ignore_errors=True)


def answers(port: int) -> bool:
    try:
        status, _, _ = Visitor(port).get('/hub/login')
    except OSError:
        return False
    return status == 200


class Visitor:
    """One visitor of the hub with its cookies (the hub's certificate is self-signed)."""

    def __init__(self, port: int) -> None:
        self.port = port
        # A browser's cookie rules (paths, expiry): a refused look at a classmate's server sets an _xsrf
        # cookie for that server's path, which must not replace the one of the student's own.
        self.cookies = http.cookiejar.CookieJar()
        self.peer_certificate = b''

    def request(self, method: str, path: str, form: dict[str, str] | None = None,
                headers: dict[str, str] | None = None) -> tuple[int, str, str]:
        """(status, Location, body) of one request."""
        connection = http.client.HTTPSConnection('127.0.0.1', self.port, timeout=30,
                                                 context=ssl._create_unverified_context())
        asked = urllib.request.Request(self.url(path), method=method)
        self.cookies.add_cookie_header(asked)
        headers = {**(headers or {}), **dict(asked.header_items())}
        body = None
        if form is not None:
            body = urllib.parse.urlencode(form)
            headers['Content-Type'] = 'application/x-www-form-urlencoded'
        try:
            connection.request(method, path, body=body, headers=headers)
            assert connection.sock is not None
            self.peer_certificate = connection.sock.getpeercert(binary_form=True) or b''
            response = connection.getresponse()
            text = response.read().decode(errors='replace')
        finally:
            connection.close()
        self.cookies.extract_cookies(response, asked)
        return response.status, response.getheader('Location') or '', text

    def url(self, path: str) -> str:
        return f'https://127.0.0.1:{self.port}{path}'

    def cookie_header(self, path: str) -> str:
        """The Cookie header a browser sends with a request for path."""
        asked = urllib.request.Request(self.url(path))
        self.cookies.add_cookie_header(asked)
        return asked.get_header('Cookie', '')

    def cookie(self, name: str, path: str) -> str:
        """The value of the cookie called name that a request for path carries ('' when none does)."""
        pairs = (pair.partition('=') for pair in self.cookie_header(path).split('; '))
        return next((value for key, _, value in pairs if key == name), '')

    def get(self, path: str) -> tuple[int, str, str]:
        return self.request('GET', path)

    def open(self, path: str, redirects: int = 6) -> tuple[int, str]:
        """The status and page at the end of path's redirects (within this hub), as a browser shows it."""
        for _ in range(redirects):
            status, location, body = self.get(path)
            if status not in (301, 302, 303, 307) or not location.startswith('/'):
                break
            path = location
        return status, body

    def follow(self, path: str) -> int:
        """The status at the end of path's redirects."""
        return self.open(path)[0]

    def log_in(self, name: str, password: str) -> tuple[int, str, str]:
        _, _, page = self.get('/hub/login')
        xsrf = re.search(r'name="_xsrf" value="([^"]+)"', page)
        return self.request('POST', '/hub/login', {'username': name, 'password': password,
                                                   '_xsrf': xsrf.group(1) if xsrf else ''})


class Terminal:
    """A JupyterLab terminal of a logged-in student, driven over its WebSocket as the lab page does."""

    def __init__(self, browser: Visitor, name: str) -> None:
        self.browser, self.name = browser, name
        self.output = ''
        self.session: aiohttp.ClientSession | None = None
        self.socket: aiohttp.ClientWebSocketResponse[bool] | None = None

    async def __aenter__(self) -> Terminal:
        api = f'/user/{self.name}/api/terminals'
        xsrf = self.browser.cookie('_xsrf', api)
        status, _, body = self.browser.request('POST', api, headers={'X-XSRFToken': xsrf})
        assert status == 200, body
        self.session = aiohttp.ClientSession(headers={'Cookie': self.browser.cookie_header(api)})
        self.socket = await self.session.ws_connect(
            f'wss://127.0.0.1:{self.browser.port}/user/{self.name}/terminals/websocket/{json.loads(body)["name"]}',
            ssl=False)
        return self

    async def __aexit__(self, *exc: object) -> None:
        assert self.session is not None
        await self.session.close()

    async def run(self, command: str, timeout: float = 60) -> str:
        """Type command, and what it printed until it ended (an end marker the shell expands)."""
        assert self.socket is not None
        marker = secrets.token_hex(4)
        start = len(self.output)
        # The marker's line comes after the command's (a command ending in & is one too); the shell
        # expands it, so the typed line itself never matches.
        await self.socket.send_str(json.dumps(['stdin', f'{command}\recho END-$((0x{marker}))\r']))
        ended = f'END-{int(marker, 16)}'
        try:
            await asyncio.wait_for(self.read_until(ended, start), timeout)
        except asyncio.TimeoutError:
            raise AssertionError(f'{command!r} did not end in {timeout} s:\n{self.output}') from None
        return self.output[start:self.output.index(ended, start)]

    async def read_until(self, text: str, start: int) -> None:
        assert self.socket is not None
        while text not in self.output[start:]:
            message = await self.socket.receive()
            if message.type is not aiohttp.WSMsgType.TEXT:
                raise AssertionError(f'the terminal closed ({message!r}); it showed:\n{self.output}')
            kind, *data = json.loads(message.data)
            if kind == 'stdout':
                self.output += data[0]


def in_a_thread(work: Coroutine[Any, Any, Result]) -> Result:
    """asyncio.run(work) in a thread of its own: this one's loop may be Playwright's (the browser fixture)."""
    with ThreadPoolExecutor(1) as pool:
        return pool.submit(asyncio.run, work).result()


def remove_accounts(names: set[str]) -> None:
    for name in names:
        subprocess.run(['userdel', '--remove', name], capture_output=True, check=False)


def logged_in(hub: Hub, names: list[str], timeout: float = 180.0) -> dict[str, Visitor]:
    """Each of names logged in with their server running, as their browser is once the lab shows.

    timeout: seconds for each server to answer (JupyterLab starts in about 10 s alone, several at
    once on a loaded 2-core machine take minutes).
    """
    students = {name: Visitor(hub.port) for name in names}
    for name, student in students.items():
        status, location, _ = student.log_in(name, hub.students[name])
        assert (status, location) in {(302, '/hub/spawn'), (302, f'/user/{name}/')}  # to start, or running
        assert student.get('/hub/spawn')[0] == 302
    for name, student in students.items():
        # The lab page logs the browser in to the server (OAuth through the hub); then its API answers
        # (api/status needs that login, while a server's bare api/ answers anyone with its version).
        wait_until(lambda: student.follow(f'/user/{name}/lab') == 200  # noqa: B023
                   and student.get(f'/user/{name}/api/status')[0] == 200, timeout,  # noqa: B023
                   f"{name}'s server")
    return students


