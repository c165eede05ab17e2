"""`owl class serve` with a real JupyterHub, real PAM logins and real Unix accounts (as root).

One hub serves the module: the students log in over HTTPS (the self-signed certificate's fingerprint
checked against the one printed), a wrong password and an unknown name are refused, a student cannot
reach the admin API, the admin page or another student's server, each student's server runs as
their own account, homes are private, and a restart with a longer class list adds a student and
keeps the others' files. Every account made here is removed at the end.
"""

from __future__ import annotations

import hashlib
import http.client
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
import urllib.parse
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from gates import prerequisite_missing
from owl_common.processes import RosProcess
from ros_harness import wait_until
from web_harness import free_port

START_TIMEOUT = 240.0  # s: the first start installs JupyterHub into its own venv
# The hub's tests start it (installing it first on a new machine) and a JupyterLab per student: about
# a core's worth, for tens of seconds alone and minutes on a loaded machine. They take the share of
# the machine the whole kit does, and time enough that a slow start is a failure, not a dead worker.
HUB_TEST_TIMEOUT = 360.0  # s
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

    def request(self, method: str, path: str, form: dict[str, str] | None = None) -> tuple[int, str, str]:
        """(status, Location, body) of one request."""
        connection = http.client.HTTPSConnection('127.0.0.1', self.port, timeout=30,
                                                 context=ssl._create_unverified_context())
        headers = {'Cookie': '; '.join(f'{k}={v}' for k, v in self.cookies.items())}
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

    def follow(self, path: str, redirects: int = 5) -> int:
        """The status at the end of path's redirects (within this hub)."""
        for _ in range(redirects):
            status, location, _ = self.get(path)
            if status not in (301, 302, 303, 307) or not location.startswith('/'):
                return status
            path = location
        return status

    def log_in(self, name: str, password: str) -> tuple[int, str, str]:
        _, _, page = self.get('/hub/login')
        xsrf = re.search(r'name="_xsrf" value="([^"]+)"', page)
        return self.request('POST', '/hub/login', {'username': name, 'password': password,
                                                   '_xsrf': xsrf.group(1) if xsrf else ''})


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


@pytest.mark.whole_kit
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_students_log_in_to_servers_of_their_own_and_reach_nothing_else(hub):
    first, second = hub.students
    visitor = Browser(hub.port)
    assert visitor.log_in(first, 'not-the-password')[0] == 403
    assert visitor.log_in('nosuchstudent', 'x')[0] == 403
    expected = hashlib.sha256(visitor.peer_certificate).hexdigest().upper()
    assert hub.fingerprint.replace(':', '') == expected  # the students compare what the teacher printed

    students = {name: Browser(hub.port) for name in (first, second)}
    for name, student in students.items():
        status, location, _ = student.log_in(name, hub.students[name])
        assert (status, location) == (302, '/hub/spawn')
        assert student.get('/hub/spawn')[0] == 302
    for name, student in students.items():
        # The lab page logs the browser in to the server (OAuth through the hub); then its API answers
        # (api/status needs that login, while a server's bare api/ answers anyone with its version).
        wait_until(lambda: student.follow(f'/user/{name}/lab') == 200  # noqa: B023
                   and student.get(f'/user/{name}/api/status')[0] == 200, 90, f"{name}'s server")  # noqa: B023
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
def test_a_restart_with_a_longer_list_adds_a_student_and_keeps_everyones_files(hub):
    first = next(iter(hub.students))
    work = Path(pwd.getpwnam(first).pw_dir) / 'work.py'
    work.write_text('print("kept")\n')
    assert hub.process is not None
    hub.process.send_signal(signal.SIGTERM)  # as `kill` would: the hub stops with it, as at Ctrl-C
    assert hub.process.wait(30) == 0
    assert server_processes_of(first) == []  # the students' servers stopped too
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

