"""`owl class serve` with a real JupyterHub, real PAM logins and real Unix accounts (as root).

One hub of three students serves the module: they log in over HTTPS (the self-signed certificate's
fingerprint checked against the one printed), a wrong password and an unknown name are refused, a
student cannot reach the admin API, the admin page, the teacher's page or another student's server,
each student's server runs as their own account, homes are private; each has a terminal of the lab
and a ROS world of their own, starts the kit and opens its pages in Chromium through the hub; the
teacher's page shows their `owl check` results; a restart with a longer class list adds a student
and keeps the others' files. Every account made here is removed at the end (tests/class_harness.py).
"""

from __future__ import annotations

import asyncio
import hashlib
import json
import os
import pty
import pwd
import re
import select
import signal
import socket
import subprocess
import tempfile
import time
from collections.abc import Iterator
from contextlib import AsyncExitStack
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest
from class_harness import (
    TEACHER_PASSWORD,
    Hub,
    Terminal,
    Visitor,
    in_a_thread,
    logged_in,
    new_name,
    remove_accounts,
)
from gates import prerequisite_missing
from ros_harness import wait_until
from web_harness import VIEWPORT, BrowserPage, check_module_pages, free_port, open_from_index

# The hub's tests start it (installing it first on a new machine) and a JupyterLab per student: about
# a core's worth, for tens of seconds alone and minutes on a loaded machine. They take the share of
# the machine the whole kit does, and time enough that a slow start is a failure, not a dead worker.
HUB_TEST_TIMEOUT = 540.0  # s


@pytest.fixture(scope='module')
def hub() -> Iterator[Hub]:
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    started = Hub.open(students=3)
    try:
        yield started
    finally:
        process = started.process
        assert started.close() == 0  # Ctrl-C ends the class server cleanly
        assert process is not None
        assert 'Traceback' not in process.output  # nor of the hub's services (the teacher's page)


def server_processes_of(name: str) -> list[str]:
    listing = subprocess.run(['ps', '-ww', '-o', 'args=', '-u', name], capture_output=True, text=True,
                             check=False)
    return [line for line in listing.stdout.splitlines() if 'jupyterhub-singleuser' in line]


@pytest.mark.whole_kit
@pytest.mark.class_lab
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_students_log_in_to_servers_of_their_own_and_reach_nothing_else(hub):
    first, second, _ = hub.students
    visitor = Visitor(hub.port)
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
@pytest.mark.class_lab
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_each_student_has_a_terminal_of_the_lab_a_ros_world_and_a_front_door_of_their_own(hub):
    names = list(hub.students)
    first, second, _ = names
    students = logged_in(hub, names)

    def turtles(listing: str) -> int:
        plain = re.sub(r'\x1b\[[0-9;?]*[A-Za-z]', '', listing)  # the terminal's own escapes (bracketed paste)
        return sum(line.strip() == '/turtlesim' for line in plain.splitlines())

    async def in_terminals() -> None:
        async with AsyncExitStack() as stack:
            terminals = [await stack.enter_async_context(Terminal(students[name], name)) for name in names]
            domains = [re.findall(r'domain (\d+)', await terminal.run('echo "domain $ROS_DOMAIN_ID"'))
                       for terminal in terminals]
            assert sorted(len(found) for found in domains) == [1, 1, 1], domains
            assert len({found[0] for found in domains}) == len(names)
            for terminal in terminals:  # as the course has it, section 3: every student's own turtle
                await terminal.run('ros2 run turtlesim turtlesim_node > turtlesim.log 2>&1 &')
            deadline = time.monotonic() + 60
            for terminal in terminals:
                while not turtles(await terminal.run('ros2 node list')):
                    assert time.monotonic() < deadline, terminal.output  # each listing waits for discovery
            for terminal in terminals:  # all three run now: in one world each would list three
                assert turtles(await terminal.run('ros2 node list')) == 1, terminal.output
            assert all('Owl Kit Lab: network private' in t.output for t in terminals)  # the lab's env.sh

    in_a_thread(in_terminals())
    # The launcher's tile: the student's front door, through the hub's proxy; nobody else's.
    wait_until(lambda: 'Owl Kit Lab: every page' in students[first].get(f'/user/{first}/owl-kit-lab/')[2],
               60, f"{first}'s front door")
    assert students[second].follow(f'/user/{first}/owl-kit-lab/') == 403
    # Nor through 127.0.0.1, which every account of the machine shares.
    assert 'refused: these pages are for account uid' in in_a_thread(
        peek(students[second], second, hub.front_door(first)))


async def peek(student: Visitor, name: str, url: str) -> str:
    """What a student's terminal gets from url: a classmate's page is on this machine's 127.0.0.1 too."""
    async with Terminal(student, name) as terminal:
        parts = urlsplit(url)
        answer = await terminal.run(
            'python3 -c "import http.client; '
            f"c = http.client.HTTPConnection('{parts.hostname}', {parts.port}); "
            f"c.request('GET', '{parts.path or '/'}'); a = c.getresponse(); print('answer', a.status, "
            'a.read().decode())"')
        assert 'answer 403 ' in answer, answer
        return answer


def row_of(table: str, name: str) -> str:
    found = re.search(rf'<tr data-student="{name}">(.*?)</tr>', table)
    assert found, table
    return found.group(1)


@pytest.mark.whole_kit
@pytest.mark.class_lab
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_the_teachers_page_shows_each_students_owl_check_and_no_student_opens_it(hub, browser):
    passing, failing, idle = hub.students
    students = logged_in(hub, [passing, failing, idle])
    teacher = Visitor(hub.port)
    assert teacher.log_in(hub.teacher, TEACHER_PASSWORD)[0] == 302
    status, page = teacher.open('/services/owl-teacher/')
    assert status == 200, page
    assert 'not-run" data-exercise="imu_turtle"' in row_of(page, passing)
    for student in students.values():
        assert student.follow('/services/owl-teacher/') == 403  # the hub refuses them the service
        assert student.follow('/services/owl-teacher/api/table') == 403

    async def checks() -> list[str]:
        # As section 4.3 has it: the package in their own workspace, built there, then checked; one
        # student's with the course's solution, one's with the IMU's axes swapped.
        packages = {passing: 'src/course/olive_imu',
                    failing: 'tests/owl_check_variants/imu_swapped/olive_imu'}

        async def check(name: str) -> str:
            async with Terminal(students[name], name) as terminal:
                command = (f'mkdir -p ~/ros2_ws/src && cp -r "$OWL_ROOT/{packages[name]}" ~/ros2_ws/src/ '
                           '&& cd ~/ros2_ws && owl check imu_turtle')
                return await terminal.run(command, timeout=240)

        return list(await asyncio.gather(check(passing), check(failing)))

    async def refusals() -> str:  # what the page says to results it must not keep
        script = hub.folder / 'send_bad_results.py'  # the hub's folder: every account may read it
        script.write_text(SEND_BAD_RESULTS)
        script.chmod(0o644)
        async with Terminal(students[idle], idle) as terminal:
            return await terminal.run(f'python3 {script}')

    view = BrowserPage(browser.chromium.new_page(viewport=VIEWPORT, ignore_https_errors=True))
    try:  # the teacher keeps the page open while the students check their work
        log_in_with_chromium(view, hub, hub.teacher, TEACHER_PASSWORD, '/services/owl-teacher/')
        view.wait_for_selector(f'tr[data-student="{passing}"] span.not-run[data-exercise="imu_turtle"]')
        passed, failed = in_a_thread(checks())
        assert 'imu_turtle: passed' in passed, passed
        assert 'imu_turtle: FAILED' in failed, failed
        assert "the teacher's page did not take" not in passed + failed
        refused = in_a_thread(refusals())
        no_token = "answer 403 send the results with your server's token"
        assert refused.count(no_token) == 2, refused  # none, and a forged one
        assert 'answer 400 results must be JSON' in refused, refused
        table = teacher.get('/services/owl-teacher/api/table')[2]  # what the page's refresh fetches
        assert 'class="passed" data-exercise="imu_turtle"' in row_of(table, passing)
        assert 'class="failed" data-exercise="imu_turtle"' in row_of(table, failing)
        assert 'class="not-run" data-exercise="imu_turtle"' in row_of(table, idle)
        assert '<td class="last">just now</td>' in row_of(table, passing)
        view.wait_for_selector(f'tr[data-student="{passing}"] span.passed[data-exercise="imu_turtle"]',
                               timeout=15_000)  # the open page shows the results by itself
        view.wait_for_selector(f'tr[data-student="{failing}"] span.failed[data-exercise="imu_turtle"]',
                               timeout=15_000)
        assert view.is_hidden('#stale')
        assert view.inner_text(f'tr[data-student="{passing}"] td.sum').startswith('1 of ')
        view.locator(f'tr[data-student="{failing}"] span.failed').scroll_into_view_if_needed()
        view.screenshot_to('class_teacher_page')  # the names stay in view beside section 4.3
        view.context.clear_cookies()  # signed out: the page says so and keeps what it showed
        view.wait_for_selector('#stale:text("signed out: reload the page")', timeout=15_000)
        assert view.locator(f'tr[data-student="{passing}"] span.passed').count() == 1
        assert all('403' in error for error in view.console_errors), view.console_errors
    finally:
        view.context.close()


# Sent from a student's terminal: results without a token, with a forged one, and not JSON.
SEND_BAD_RESULTS = '''
import json, os, urllib.error, urllib.request
for token, body in [('', b'{}'), ('forged-token', b'{}'), (os.environ['JUPYTERHUB_API_TOKEN'], b'not json')]:
    headers = {'Authorization': f'token {token}'} if token else {}
    request = urllib.request.Request(os.environ['OWL_CLASS_RESULTS_URL'], data=body, headers=headers)
    try:
        urllib.request.urlopen(request, timeout=10)
        print('answer 200')
    except urllib.error.HTTPError as error:
        print('answer', error.code, json.loads(error.read())['error'])
'''


def log_in_with_chromium(page: Any, hub: Hub, name: str, password: str, then: str) -> None:
    """The hub's login form filled in and sent in Chromium, waiting for the page at then (a path)."""
    hub_url = f'https://127.0.0.1:{hub.port}'
    page.goto(f'{hub_url}/hub/login?next={then}')
    page.fill('input[name=username]', name)
    page.fill('input[name=password]', password)
    page.click('[type=submit]')
    page.wait_for_url(f'{hub_url}{then}**', timeout=90_000)


@pytest.mark.whole_kit
@pytest.mark.class_lab
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_students_in_chromium_start_their_kits_and_open_their_own_pages_through_the_hub(hub, browser):
    hub_url = f'https://127.0.0.1:{hub.port}'
    students = logged_in(hub, list(hub.students))

    async def start_the_kits() -> None:
        for name, student in students.items():  # the same ports asked for: each gets pages of their own
            async with Terminal(student, name) as terminal:
                await terminal.run('ros2 launch robot_view robot_view.launch.py > robot_view.log 2>&1 &')

    in_a_thread(start_the_kits())
    robot_views = {}
    for name, password in hub.students.items():
        lab = browser.chromium.new_page(viewport=VIEWPORT, ignore_https_errors=True)  # self-signed
        try:
            log_in_with_chromium(lab, hub, name, password, f'/user/{name}/lab')
            tile = lab.locator('.jp-LauncherCard', has_text='Owl Kit Lab pages')
            tile.wait_for(timeout=60_000)  # the launcher's tile for the front door
            with lab.expect_popup() as opened:
                tile.click()
            pages = BrowserPage(opened.value)
            base = f'{hub_url}/user/{name}/owl-kit-lab/'
            pages.wait_for_url(base, timeout=30_000)
            pages.wait_for_selector('li.running[data-mount="robot-view"]', timeout=90_000)  # the kit started
            robot_views[name] = (pages.evaluate(
                'fetch("api/pages").then((answer) => answer.json())'
                '.then((all) => all.find((page) => page.mount === "robot-view").url)'))
            open_from_index(pages, base, 'robot-view')
            pages.wait_for_function('() => window.robotView.imu !== null && window.robotView.servos '
                                    '&& window.robotView.servos.pan.kp !== null', timeout=30_000)
            before = pages.evaluate('JSON.stringify(window.robotView.imu)')
            pages.wait_for_function(f'() => JSON.stringify(window.robotView.imu) !== {json.dumps(before)}',
                                    timeout=10_000)  # live, through the hub's proxy and the front door
            check_module_pages(pages, base)
            pages.forgive_server_away()
            assert pages.console_errors == []
        finally:
            lab.context.close()
    assert len(set(robot_views.values())) == len(hub.students)  # three robot views, on three ports
    first, second, _ = hub.students  # a classmate's robot view at its own port refuses too
    assert 'refused: these pages are for account uid' in in_a_thread(
        peek(students[second], second, robot_views[first]))


@pytest.mark.whole_kit
@pytest.mark.class_lab
@pytest.mark.timeout(HUB_TEST_TIMEOUT)
def test_a_restart_with_a_longer_list_adds_a_student_and_keeps_everyones_files(hub):
    first = next(iter(hub.students))
    works = {name: Path(pwd.getpwnam(name).pw_dir) / 'work.py' for name in hub.students}
    for name, work in works.items():  # each one's home: their workspace and everything else of theirs
        work.write_text(f'print("{name} kept")\n')
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
    for name, work in works.items():
        assert work.read_text() == f'print("{name} kept")\n'
    assert Visitor(hub.port).log_in(newcomer, 'pw-newcomer')[:2] == (302, '/hub/spawn')
    assert Visitor(hub.port).log_in(first, hub.students[first])[:2] == (302, '/hub/spawn')
    assert Visitor(hub.port).log_in(hub.teacher, TEACHER_PASSWORD)[:2] == (302, '/hub/spawn')


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


@pytest.mark.parametrize(('certificate', 'message'), [
    (['--cert', '{folder}/hub.crt'], 'give both --cert and --key, or neither'),
    (['--cert', '{folder}/missing.crt', '--key', '{folder}/missing.key'],
     '--cert {folder}/missing.crt: no such file'),
    (['--cert', '{folder}/not-pem.crt', '--key', '{folder}/not-pem.crt'], 'cannot read the certificate'),
])
def test_a_wrong_certificate_is_one_line_and_creates_nothing(tmp_path, certificate, message):
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    (tmp_path / 'not-pem.crt').write_text('not a certificate\n')
    student = new_name()
    class_list = tmp_path / 'class.txt'
    class_list.write_text(f'{student} pw-a\n')
    done = subprocess.run(['owl', 'class', 'serve', '--students', str(class_list), '--teacher', new_name(),
                           '--port', str(free_port()), '--state', str(tmp_path / 'state'),
                           *(arg.format(folder=tmp_path) for arg in certificate)],
                          capture_output=True, text=True, timeout=60, check=False,
                          env={**os.environ, 'OWL_CLASS_TEACHER_PASSWORD': TEACHER_PASSWORD})
    assert done.returncode == 2
    [line] = done.stderr.strip().splitlines()
    assert line.startswith(f"owl class: {message.format(folder=tmp_path)}"), line
    assert not (tmp_path / 'state').exists()
    with pytest.raises(KeyError):
        pwd.getpwnam(student)


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



def read_until(terminal: int, text: str, timeout: float = 30) -> str:
    """What the terminal (a pty's master) shows until text, or until the program ends."""
    seen, deadline = '', time.monotonic() + timeout
    while text not in seen:
        assert time.monotonic() < deadline, seen
        ready, _, _ = select.select([terminal], [], [], 1)
        if ready:
            try:
                chunk = os.read(terminal, 4096)
            except OSError:  # the program ended: its side of the pty is closed
                break
            if not chunk:
                break
            seen += chunk.decode(errors='replace')
    return seen


def test_the_teachers_password_is_asked_in_a_terminal_and_a_bad_one_is_one_line(tmp_path):
    if os.geteuid() != 0:
        prerequisite_missing('owl class serve makes Unix accounts: the test runs as root')
    class_list = tmp_path / 'class.txt'
    student, teacher = new_name(), new_name()
    class_list.write_text(f'{student} pw-a\n')
    folder = Path(tempfile.mkdtemp(prefix='owl-class-test-'))  # one every account may pass through
    folder.chmod(0o711)
    argv = ['owl', 'class', 'serve', '--students', str(class_list), '--teacher', teacher,
            '--port', str(free_port()), '--state', str(folder / 'state')]
    env = {name: value for name, value in os.environ.items() if name != 'OWL_CLASS_TEACHER_PASSWORD'}
    unasked = subprocess.run(argv, capture_output=True, text=True, timeout=60, check=False, env=env,
                             stdin=subprocess.DEVNULL)
    assert unasked.returncode == 2
    assert unasked.stderr.strip().splitlines() == [
        'owl class: set OWL_CLASS_TEACHER_PASSWORD or run it in a terminal to be asked the teacher\'s '
        'password']
    pid, terminal = pty.fork()
    if pid == 0:  # the child: the teacher's terminal runs the command
        os.execvpe(argv[0], argv, env)
    try:
        assert "The teacher's password: " in read_until(terminal, "The teacher's password: ")
        os.write(terminal, b'two words\n')
        shown = read_until(terminal, 'without spaces')
        assert "owl class: the teacher's password must be non-empty, without spaces" in shown, shown
        assert 'two words' not in shown  # not echoed
    finally:
        _, status = os.waitpid(pid, 0)
        os.close(terminal)
    assert os.waitstatus_to_exitcode(status) == 2
    assert list(folder.iterdir()) == []
    folder.rmdir()
    for name in (student, teacher):
        with pytest.raises(KeyError):
            pwd.getpwnam(name)
