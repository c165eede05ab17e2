"""`owl class serve` with a real JupyterHub, real PAM logins and real Unix accounts (as root).

One hub serves the module: the students log in over HTTPS (the self-signed certificate's fingerprint
checked against the one printed), a wrong password and an unknown name are refused, a student cannot
reach the admin API, the admin page or another student's server, each student's server runs as
their own account, homes are private, and a restart with a longer class list adds a student and
keeps the others' files. Every account made here is removed at the end.
"""

from __future__ import annotations

import asyncio
import hashlib
import http.client
import json
import os
import pwd
import re
import secrets
import shutil
import signal
import socket
import ssl
import subprocess
import tempfile
import time
import urllib.parse
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import aiohttp
import pytest
from gates import prerequisite_missing
from owl_common.processes import RosProcess
from ros_harness import wait_until
from web_harness import free_port

START_TIMEOUT = 300.0  # s: the first start installs JupyterHub and builds the students' lab
# The hub's tests start it (installing it first on a new machine) and a JupyterLab per student: about
# a core's worth, for tens of seconds alone and minutes on a loaded machine. They take the share of
# the machine the whole kit does, and time enough that a slow start is a failure, not a dead worker.
HUB_TEST_TIMEOUT = 540.0  # s
TEACHER_PASSWORD = 'teacher-secret-1'


def new_name() -> str:
    return f'owl{secrets.token_hex(3)}'


@dataclass
class Hub:
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
                           '--port', str(self.port), '--state', str(self.folder / 'state')], env,
                          label='owl class serve')

    def start(self) -> None:
        self.made |= {*self.students, self.teacher}
        self.process = self.command(self.write_list())
        line = self.process.wait_for(r'certificate SHA-256 ([0-9A-F:]+)\)', START_TIMEOUT)[0]
        self.fingerprint = line.group(1)
        wait_until(lambda: answers(self.port), 30, 'the hub answering')

    def stop(self) -> int:
        assert self.process is not None
        return self.process.stop(timeout=20)


def answers(port: int) -> bool:
    try:
        status, _, _ = Browser(port).get('/hub/login')
    except OSError:
        return False
    return status == 200


class Browser:
    """One visitor of the hub with its cookies (the hub's certificate is self-signed)."""

    def __init__(self, port: int) -> None:
        self.port = port
        self.cookies: dict[str, str] = {}
        self.peer_certificate = b''

    def request(self, method: str, path: str, form: dict[str, str] | None = None,
                headers: dict[str, str] | None = None) -> tuple[int, str, str]:
        """(status, Location, body) of one request."""
        connection = http.client.HTTPSConnection('127.0.0.1', self.port, timeout=30,
                                                 context=ssl._create_unverified_context())
        headers = {**(headers or {}), 'Cookie': '; '.join(f'{k}={v}' for k, v in self.cookies.items())}
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
        for name, value in response.getheaders():
            if name.lower() == 'set-cookie':
                key, _, rest = value.partition('=')
                self.cookies[key] = rest.split(';')[0]
        return response.status, response.getheader('Location') or '', text

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

    def __init__(self, browser: Browser, name: str) -> None:
        self.browser, self.name = browser, name
        self.output = ''
        self.session: aiohttp.ClientSession | None = None
        self.socket: aiohttp.ClientWebSocketResponse[bool] | None = None

    async def __aenter__(self) -> Terminal:
        status, _, body = self.browser.request('POST', f'/user/{self.name}/api/terminals',
                                               headers={'X-XSRFToken': self.browser.cookies.get('_xsrf', '')})
        assert status == 200, body
        cookie = '; '.join(f'{k}={v}' for k, v in self.browser.cookies.items())
        self.session = aiohttp.ClientSession(headers={'Cookie': cookie})
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


def remove_accounts(names: set[str]) -> None:
    for name in names:
        subprocess.run(['userdel', '--remove', name], capture_output=True, check=False)


@pytest.fixture(scope='module')
def hub(tmp_path_factory) -> Iterator[Hub]:
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    # Not under pytest's own folder, which only root may pass through: every student runs the venv inside.
    folder = Path(tempfile.mkdtemp(prefix='owl-class-test-'))
    folder.chmod(0o711)
    students = {new_name(): f'pw-{secrets.token_hex(4)}' for _ in range(2)}
    started = Hub(folder, free_port(), new_name(), students)
    try:
        started.start()
        yield started
    finally:
        try:
            if started.process is not None:
                assert started.stop() == 0  # Ctrl-C ends the class server cleanly
        finally:
            remove_accounts(started.made)
            shutil.rmtree(folder, ignore_errors=True)


def server_processes_of(name: str) -> list[str]:
    listing = subprocess.run(['ps', '-ww', '-o', 'args=', '-u', name], capture_output=True, text=True,
                             check=False)
    return [line for line in listing.stdout.splitlines() if 'jupyterhub-singleuser' in line]


def logged_in(hub: Hub, names: list[str]) -> dict[str, Browser]:
    """Each of names logged in with their server running, as their browser is once the lab shows."""
    students = {name: Browser(hub.port) for name in names}
    for name, student in students.items():
        status, location, _ = student.log_in(name, hub.students[name])
        assert (status, location) in {(302, '/hub/spawn'), (302, f'/user/{name}/')}  # to start, or running
        assert student.get('/hub/spawn')[0] == 302
    for name, student in students.items():
        # The lab page logs the browser in to the server (OAuth through the hub); then its API answers
        # (api/status needs that login, while a server's bare api/ answers anyone with its version).
        wait_until(lambda: student.follow(f'/user/{name}/lab') == 200  # noqa: B023
                   and student.get(f'/user/{name}/api/status')[0] == 200, 90, f"{name}'s server")  # noqa: B023
    return students


@pytest.mark.whole_kit
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_students_log_in_to_servers_of_their_own_and_reach_nothing_else(hub):
    first, second = hub.students
    visitor = Browser(hub.port)
    assert visitor.log_in(first, 'not-the-password')[0] == 403
    assert visitor.log_in('nosuchstudent', 'x')[0] == 403
    expected = hashlib.sha256(visitor.peer_certificate).hexdigest().upper()
    assert hub.fingerprint.replace(':', '') == expected  # the students compare what the teacher printed

    students = logged_in(hub, [first, second])
    for name in students:
        assert server_processes_of(name)  # started as the student's own account
    student = students[first]
    assert student.get('/hub/api/users')[0] == 403  # the admin API
    assert student.get('/hub/admin')[0] == 403
    assert student.follow(f'/user/{second}/lab') == 403  # the other's running server: the hub refuses
    assert student.get(f'/user/{second}/api/contents')[0] == 403

    private = Path(pwd.getpwnam(second).pw_dir) / 'notes.txt'
    private.write_text('mine')
    peek = subprocess.run(['su', first, '-s', '/bin/bash', '-c', f'cat {private}'], capture_output=True,
                          text=True, check=False)
    assert peek.returncode != 0
    assert 'Permission denied' in peek.stderr


@pytest.mark.whole_kit
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_each_student_has_a_terminal_of_the_lab_a_ros_world_and_a_front_door_of_their_own(hub):
    first, second = hub.students
    students = logged_in(hub, [first, second])

    async def in_terminals() -> None:
        async with Terminal(students[first], first) as mine, Terminal(students[second], second) as theirs:
            domains = [re.findall(r'domain (\d+)', await terminal.run('echo "domain $ROS_DOMAIN_ID"'))
                       for terminal in (mine, theirs)]
            assert len(domains[0]) == len(domains[1]) == 1, (mine.output, theirs.output)
            assert domains[0] != domains[1]
            await mine.run('ros2 run turtlesim turtlesim_node > turtlesim.log 2>&1 &')
            deadline = time.monotonic() + 60
            while '/turtlesim' not in await mine.run('ros2 node list'):
                assert time.monotonic() < deadline, mine.output  # each listing waits for discovery
            assert '/turtlesim' not in await theirs.run('ros2 node list')  # another student's world
            assert 'Owl Kit Lab: network private' in mine.output  # the terminal sourced the lab's env.sh

    asyncio.run(in_terminals())
    # The launcher's tile: the student's front door, through the hub's proxy; nobody else's.
    wait_until(lambda: 'Owl Kit Lab: every page' in students[first].get(f'/user/{first}/owl-kit-lab/')[2],
               60, f"{first}'s front door")
    assert students[second].follow(f'/user/{first}/owl-kit-lab/') == 403


def row_of(table: str, name: str) -> str:
    found = re.search(rf'<tr data-student="{name}">(.*?)</tr>', table)
    assert found, table
    return found.group(1)


@pytest.mark.whole_kit
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_the_teachers_page_shows_a_students_owl_check_and_no_student_opens_it(hub):
    first, second = hub.students
    students = logged_in(hub, [first, second])
    teacher = Browser(hub.port)
    assert teacher.log_in(hub.teacher, TEACHER_PASSWORD)[0] == 302
    status, page = teacher.open('/services/owl-teacher/')
    assert status == 200, page
    assert 'not-run" data-exercise="imu_turtle"' in row_of(page, first)

    async def a_students_check() -> str:
        # As section 4.3 has it: the package in their own workspace, built there, then checked.
        async with Terminal(students[first], first) as terminal:
            return await terminal.run('mkdir -p ~/ros2_ws/src && cp -r "$OWL_ROOT/src/course/olive_imu" '
                                      '~/ros2_ws/src/ && cd ~/ros2_ws && owl check imu_turtle', timeout=240)

    checked = asyncio.run(a_students_check())
    assert 'imu_turtle: passed' in checked, checked
    table = teacher.get('/services/owl-teacher/api/table')[2]  # what the page's refresh fetches
    assert 'class="passed" data-exercise="imu_turtle"' in row_of(table, first)
    assert 'class="not-run" data-exercise="imu_turtle"' in row_of(table, second)
    assert '<td class="last">just now</td>' in row_of(table, first)
    for student in students.values():
        assert student.follow('/services/owl-teacher/') == 403  # the hub refuses them the service
        assert student.follow('/services/owl-teacher/api/table') == 403


@pytest.mark.whole_kit
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_a_restart_with_a_longer_list_adds_a_student_and_keeps_everyones_files(hub):
    first = next(iter(hub.students))
    work = Path(pwd.getpwnam(first).pw_dir) / 'work.py'
    work.write_text('print("kept")\n')
    assert hub.process is not None
    hub.process.send_signal(signal.SIGTERM)  # as `kill` would: the hub stops with it, as at Ctrl-C
    assert hub.process.wait(30) == 0
    for name in hub.students:  # their servers stopped too, and whatever they started (a turtle, a front door)
        assert subprocess.run(['pgrep', '--uid', name], capture_output=True, text=True,
                              check=False).stdout == ''
    assert not Path(hub.folder / 'state' / 'jupyterhub.pid').exists()  # and the hub itself
    newcomer = new_name()
    hub.students[newcomer] = 'pw-newcomer'
    hub.start()
    assert work.read_text() == 'print("kept")\n'
    assert Browser(hub.port).log_in(newcomer, 'pw-newcomer')[:2] == (302, '/hub/spawn')
    assert Browser(hub.port).log_in(first, hub.students[first])[:2] == (302, '/hub/spawn')
    assert Browser(hub.port).log_in(hub.teacher, TEACHER_PASSWORD)[:2] == (302, '/hub/spawn')


@pytest.mark.parametrize(('lines', 'message'), [
    (['{a} pw-a', 'Bad pw-b'], "line 2: 'Bad' is not a name of a lowercase letter"),
    (['{a} pw-a', '{a} pw-b'], "line 2: '{a}' is listed twice"),
    (['{a} pw-a', '{teacher} pw-t'], "--teacher: '{teacher}' is also in the class list"),
    (['{a} pw-a'], 'is closed to other accounts (it needs o+x)'),
    (['root pw-r'], "an account named 'root' already exists on this machine and is not one of the class's"),
])
def test_a_bad_class_list_is_one_line_and_creates_nothing(tmp_path, lines, message):
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    names = {'a': new_name(), 'teacher': new_name()}
    class_list = tmp_path / 'class.txt'
    class_list.write_text(''.join(line.format(**names) + '\n' for line in lines))
    env = {**os.environ, 'OWL_CLASS_TEACHER_PASSWORD': TEACHER_PASSWORD}
    done = subprocess.run(['owl', 'class', 'serve', '--students', str(class_list), '--teacher',
                           names['teacher'],
                           '--port', str(free_port()), '--state', str(tmp_path / 'state')],
                          capture_output=True, text=True, env=env, timeout=60, check=False)
    try:
        assert done.returncode == 2, done.stdout + done.stderr
        [line] = done.stderr.strip().splitlines()
        assert line.startswith('owl class: '), line
        assert message.format(**names) in line, line
        assert not (tmp_path / 'state').exists()
        for name in names.values():
            with pytest.raises(KeyError):
                pwd.getpwnam(name)
    finally:
        remove_accounts(set(names.values()))


def test_a_busy_port_is_one_line(tmp_path):
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    class_list = tmp_path / 'class.txt'
    class_list.write_text(f'{new_name()} pw-a\n')
    with socket.socket() as busy:
        busy.bind(('', 0))
        busy.listen()
        port = busy.getsockname()[1]
        done = subprocess.run(['owl', 'class', 'serve', '--students', str(class_list), '--teacher',
                               new_name(), '--port', str(port), '--state', str(tmp_path / 'state')],
                              capture_output=True,
                              text=True, timeout=60, check=False,
                              env={**os.environ, 'OWL_CLASS_TEACHER_PASSWORD': TEACHER_PASSWORD})
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [f'owl class: --port {port}: Address already in use']
    assert not (tmp_path / 'state').exists()


def test_a_missing_class_list_is_one_line(tmp_path):
    done = subprocess.run(['owl', 'class', 'serve', '--students', str(tmp_path / 'missing.txt'), '--teacher',
                           'teacher'], capture_output=True, text=True, timeout=60, check=False,
                          env={**os.environ, 'OWL_CLASS_TEACHER_PASSWORD': TEACHER_PASSWORD})
    assert done.returncode == 2
    [line] = done.stderr.strip().splitlines()
    assert line.startswith('owl class: ')
    assert 'Traceback' not in done.stderr

