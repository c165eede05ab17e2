"""The front door over real sockets (no ROS): a page server joins it, and it is started as users get it.

Its process is the real one (python -m owl_web.front_door, started by the page server); the requests
are raw HTTP and aiohttp's WebSocket client, which send the Host, Origin and forged headers that a
browser never would.
"""

import asyncio
import http.client
import json
import os
import re
import signal
import socket
import subprocess
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from urllib.parse import urlsplit

import aiohttp
import pytest
from owl_web import codec, pages
from owl_web.origins import TrustedOrigins, foreign_request
from owl_web.server import WebServer

PAGE = {'mount': 'test-page', 'title': 'test page', 'start': 'python test_page.py'}
CATALOGUE = [PAGE, {'mount': 'other', 'title': 'other page', 'start': 'owl other'}]
WAIT = 10.0  # s for a process to start or stop


def run(coroutine):
    """The coroutine's result, from an event loop in a thread of its own (a browser test may run one here)."""
    with ThreadPoolExecutor(1) as thread:
        return thread.submit(asyncio.run, asyncio.wait_for(coroutine, 30)).result()


def request(url, method='GET', path='/', body=None, headers=None):
    """(status, headers, body) of one raw request to url's host and port; the path goes as it is."""
    parts = urlsplit(url)
    connection = http.client.HTTPConnection(parts.hostname, parts.port, timeout=30)
    try:
        connection.request(method, path, body=body, headers=headers or {})
        response = connection.getresponse()
        return response.status, dict(response.getheaders()), response.read()
    finally:
        connection.close()


def wait_for(condition, what, timeout=WAIT):
    deadline = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > deadline:
            raise AssertionError(f'timed out after {timeout} s waiting for {what}')
        time.sleep(0.02)


def gone(pid):
    return not pages.process_alive(pid) or open(f'/proc/{pid}/stat').read().split(') ')[1].startswith('Z')


def stop_front_door(folder):
    record = pages.front_door_record(folder)
    if record is not None:
        os.kill(record.pid, signal.SIGTERM)
        wait_for(lambda: gone(record.pid), 'the front door to stop')


class JoinedPage:
    """A page server (a page, an API route and channels) joined to a front door in its own folder."""

    def __init__(self, tmp_path, monkeypatch, folder_name='pages'):
        static = tmp_path / 'static'
        static.mkdir(exist_ok=True)
        (static / 'index.html').write_text('<!DOCTYPE html><title>test page</title>')
        (static / 'app.js').write_text('// the page')
        self.folder = tmp_path / folder_name
        monkeypatch.setenv('OWL_PAGES_DIR', str(self.folder))
        monkeypatch.setenv('OWL_FRONT_DOOR_PORT', '0')
        monkeypatch.delenv('OWL_FRONT_DOOR', raising=False)
        self.seen = []  # the requests the echo route got: (headers, body)
        self.server = WebServer('test', static, log=lambda line: None)
        self.server.route('POST', '/api/echo', self.echo)

        self.server.channel('counter', lambda subscription: subscription.send({'n': 1}))
        self.server.channel('frames',
                            lambda subscription: subscription.send_binary({'frame': 1}, b'\xff\xd8 jpeg'))
        self.server.join_front_door(PAGE, CATALOGUE)
        self.server.start()

    def echo(self, api_request):
        self.seen.append((dict(api_request.headers), api_request.body))
        return 201, {'body': api_request.json()}

    @property
    def door(self):
        return self.server.front_door

    def close(self):
        self.server.stop()
        stop_front_door(self.folder)


@pytest.fixture
def joined(tmp_path, monkeypatch):
    page = JoinedPage(tmp_path, monkeypatch)
    try:
        yield page
    finally:
        page.close()


def test_a_page_is_served_whole_under_its_mount(joined):
    assert joined.door.startswith('http://127.0.0.1:')
    assert joined.server.address == f'{joined.door}test-page/'
    status, headers, body = request(joined.door, path='/test-page/')
    assert (status, body) == (200, b'<!DOCTYPE html><title>test page</title>')
    assert headers['X-Owl-Mount'] == 'test-page'  # the page can tell it is seen through the front door
    assert request(joined.door, path='/test-page/static/app.js')[2] == b'// the page'
    assert b'OwlSocket' in request(joined.door, path='/test-page/owl/socket.js')[2]
    status, _, body = request(joined.door, 'POST', '/test-page/api/echo?x=1', b'{"kp": 2.5}',
                              {'Content-Type': 'application/json'})
    assert (status, json.loads(body)) == (201, {'body': {'kp': 2.5}})
    # no trailing slash: a relative redirect, so it works under any prefix; the query stays
    status, headers, _ = request(joined.door, path='/test-page?tab=graph')
    assert (status, headers['Location']) == (308, 'test-page/?tab=graph')


def test_the_page_server_sees_its_own_host_and_origin_and_no_cookies(joined):
    own = joined.server.url.rstrip('/')
    request(joined.door, 'POST', '/test-page/api/echo', b'{}', {
        'Origin': joined.door.rstrip('/'), 'Cookie': 'jupyterhub-session-id=secret',
        'Authorization': 'token secret', 'X-Forwarded-Host': 'elsewhere.example', 'X-Custom': 'kept'})
    headers = {name.lower(): value for name, value in joined.seen[-1][0].items()}
    assert headers['host'] == own.removeprefix('http://')
    assert headers['origin'] == own
    assert headers['x-custom'] == 'kept'
    assert not {'cookie', 'authorization', 'x-forwarded-host'} & set(headers)


async def socket_through(url, *messages, receive=5, origin=None):
    """Send messages on a WebSocket at url; (what came back, frames as (header, payload), close code)."""
    received = []
    async with aiohttp.ClientSession() as session, session.ws_connect(url, origin=origin) as socket_:
        for message in messages:
            await socket_.send_str(message if isinstance(message, str) else json.dumps(message))
        while len(received) < receive:
            answer = await socket_.receive(10)
            if answer.type == aiohttp.WSMsgType.TEXT:
                received.append(json.loads(answer.data))
            elif answer.type == aiohttp.WSMsgType.BINARY:
                received.append(codec.unpack_frame(answer.data))
            else:
                break
        return received, socket_.close_code, answer.extra if received is not None else None


def test_the_websocket_passes_message_for_message_and_closes_as_the_server_does(joined):
    url = f'{joined.door}test-page/ws'
    received, code, _ = run(socket_through(url, {'type': 'subscribe', 'id': 1, 'channel': 'counter'},
                                           {'type': 'subscribe', 'id': 2, 'channel': 'frames'},
                                           receive=2, origin=joined.door.rstrip('/')))
    assert sorted(received, key=str) == sorted([{'type': 'update', 'id': 1, 'data': {'n': 1}}, (
        {'type': 'update', 'id': 2, 'data': {'frame': 1}}, b'\xff\xd8 jpeg')], key=str)
    received, _, _ = run(socket_through(url, '{"type": ', receive=1))
    assert received[0]['type'] == 'error'  # the page server's own one line, through the front door
    # a message over the limit: the connection closes with "message too big", as at the page's own port
    # (or is reset before the client reads that: test_server.py's test_a_huge_message_closes_...)
    _, code, _ = run(socket_through(url, 'x' * (codec.MAX_BODY + 10), receive=1))
    assert code in (1009, 1006)
    # a page server that stops says so: the page's socket closes with "going away"
    joined.server.stop()
    _, code, reason = run(socket_through(url, receive=1))
    assert code == 1013
    assert reason.startswith('test page is not running; start it: python test_page.py')


def frame(text: str) -> bytes:
    """A text message as a browser sends it: one final frame, masked."""
    payload, mask = text.encode(), os.urandom(4)
    assert len(payload) < 126
    return bytes([0x81, 0x80 | len(payload)]) + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


def read_answer(connection: socket.socket) -> bytes:
    """One HTTP answer's head and its body (of Content-Length), from a raw connection."""
    data = b''
    while b'\r\n\r\n' not in data:
        data += connection.recv(65536)
    head, _, body = data.partition(b'\r\n\r\n')
    length = int(re.search(rb'(?i)content-length: *(\d+)', head).group(1)) if b'ength' in head else 0
    while len(body) < length:
        body += connection.recv(65536)
    return head


def test_a_websocket_on_a_connection_used_before_is_passed_on_message_for_message(joined):
    # Browsers open a WebSocket on a connection of its own, which the front door passes through as
    # bytes; a client that first asks for something on the same connection gets the message relay.
    port = urlsplit(joined.door).port
    with socket.create_connection(('127.0.0.1', port), timeout=10) as connection:
        connection.sendall(b'GET /test-page/static/app.js HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n')
        assert read_answer(connection).startswith(b'HTTP/1.1 200')
        connection.sendall(b'GET /test-page/ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\n'
                           b'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
                           b'Sec-WebSocket-Version: 13\r\n\r\n')
        head = b''
        while b'\r\n\r\n' not in head:
            head += connection.recv(1)
        assert head.startswith(b'HTTP/1.1 101')
        connection.sendall(frame(json.dumps({'type': 'subscribe', 'id': 7, 'channel': 'counter'})))
        first = connection.recv(2)
        assert first[0] == 0x81  # a text message, unmasked from the server
        body = connection.recv(first[1] & 0x7f, socket.MSG_WAITALL)
        assert json.loads(body) == {'type': 'update', 'id': 7, 'data': {'n': 1}}


def test_the_index_lists_every_page_greys_stopped_ones_and_says_how_to_start_them(joined):
    status, headers, body = request(joined.door)
    text = body.decode()
    assert status == 200
    assert headers['Content-Type'].startswith('text/html')
    assert '<li class="page running" data-mount="test-page">' in text
    assert '<a href="./test-page/">test page</a>' in text
    assert '<li class="page stopped" data-mount="other">' in text
    assert 'start it: <code>owl other</code>' in text
    assert 'http://' not in text.replace(joined.server.url, '')  # no absolute link but the page's own address
    status, _, body = request(joined.door, path='/api/pages')
    assert [(p['mount'], p['running']) for p in json.loads(body)] == [('test-page', True), ('other', False)]
    # a page that is not running: 503 with its start command; an unknown one: 404 listing the pages
    status, _, body = request(joined.door, path='/other/')
    assert status == 503
    assert 'other page is not running; start it: owl other' in body.decode()
    status, _, body = request(joined.door, path='/nothing/deep/path.html')
    assert status == 404
    assert "No page 'nothing' here. These are the pages:" in body.decode()
    assert '<a href="../../test-page/">test page</a>' in body.decode()  # relative from where it was asked
    status, _, body = request(joined.door, 'POST', '/other/api/echo', b'{}')
    assert (status, json.loads(body)) == (503, {'error': 'other page is not running; start it: owl other'})
    assert request(joined.door, 'PUT', '/api/pages')[0] == 405
    # stopped: greyed, with its command, and its address answers 503
    joined.server.stop()
    text = request(joined.door)[2].decode()
    assert '<li class="page stopped" data-mount="test-page">' in text
    assert 'start it: <code>python test_page.py</code>' in text
    assert request(joined.door, path='/test-page/')[0] == 503


def test_a_page_killed_without_a_word_is_greyed(joined):
    entry = pages.registered(joined.folder)['test-page']
    pages.register(pages.Page(**{**entry.__dict__, 'pid': 999_999_999}), joined.folder)
    assert '<li class="page stopped" data-mount="test-page">' in request(joined.door)[2].decode()
    assert request(joined.door, path='/test-page/')[0] == 503


async def open_socket(door, origin=None):
    """'open' when the test page's WebSocket opens through the front door, else the refusal's status."""
    async with aiohttp.ClientSession() as session:
        try:
            async with session.ws_connect(f'{door}test-page/ws', origin=origin):
                return 'open'
        except aiohttp.WSServerHandshakeError as error:
            return error.status


def test_foreign_hosts_origins_and_forged_proxy_headers_are_refused_and_change_nothing(joined):
    attempts = [
        {'Host': 'rebound.example'},
        {'Host': 'rebound.example', 'X-Forwarded-Host': '127.0.0.1', 'Forwarded': 'host=127.0.0.1'},
        {'Origin': 'https://evil.example'},
        {'Origin': 'https://evil.example', 'X-Forwarded-For': '127.0.0.1', 'Forwarded': 'for=127.0.0.1'},
        {'Origin': 'null'},
    ]
    for headers in attempts:
        for path in ('/test-page/api/echo', '/', '/api/pages'):
            status, _, body = request(joined.door, 'POST' if 'echo' in path else 'GET', path, b'{}', headers)
            assert status == 403, (headers, path)
            assert json.loads(body)['error'].startswith('refused: '), body
    assert joined.seen == []  # nothing reached the page's server

    assert run(open_socket(joined.door, 'https://evil.example')) == 403
    assert run(open_socket(joined.door, joined.door.rstrip('/'))) == 'open'


def test_a_trusted_proxy_is_configured_explicitly(tmp_path, monkeypatch):
    assert TrustedOrigins.parse('https://hub.example.edu, http://Lab.local:8000') == TrustedOrigins(
        frozenset({'https://hub.example.edu', 'http://lab.local:8000'}),
        frozenset({'hub.example.edu', 'lab.local:8000'}))
    assert TrustedOrigins.parse('https://hub.example.edu:443/').hosts == {'hub.example.edu'}
    for bad in ('hub.example.edu', 'https://hub.example.edu/user/x', 'ftp://hub.example.edu', 'https://me@hub',
                'http://hub:99999', 'https://hub?x=1', 'https://'):
        with pytest.raises(ValueError, match=re.escape(f"OWL_TRUSTED_ORIGINS: '{bad}' is not an origin ")):
            TrustedOrigins.parse(bad)
    trusted = TrustedOrigins.parse('https://hub.example.edu')
    assert foreign_request('hub.example.edu', 'https://hub.example.edu', trusted) is None
    assert foreign_request('hub.example.edu', None, trusted) is None
    assert foreign_request('hub.example.edu', 'https://evil.example', trusted) == \
        'refused: a page of https://evil.example may not use this server'
    assert foreign_request('hub.example.edu:8443', None, trusted).startswith(
        "refused: Host 'hub.example.edu:8443'")
    assert foreign_request('evil.example', 'https://hub.example.edu', trusted).startswith('refused: Host')
    # over the wire, through a front door started with the setting (it comes from the environment)
    monkeypatch.setenv('OWL_TRUSTED_ORIGINS', 'http://hub.owl.test:8000')
    page = JoinedPage(tmp_path, monkeypatch)
    try:
        proxied = {'Host': 'hub.owl.test:8000', 'Origin': 'http://hub.owl.test:8000'}
        assert request(page.door, 'POST', '/test-page/api/echo', b'{}', proxied)[0] == 201
        assert request(page.server.url, 'POST', '/api/echo', b'{}', proxied)[0] == 201  # the page's own port
        for forged in ({**proxied, 'Origin': 'http://evil.test:8000'},
                       {**proxied, 'Host': 'hub.owl.test:8001'},
                       {'Host': 'evil.test', 'X-Forwarded-Host': 'hub.owl.test:8000'}):
            assert request(page.door, 'POST', '/test-page/api/echo', b'{}', forged)[0] == 403, forged
        assert len(page.seen) == 2
    finally:
        page.close()
    monkeypatch.setenv('OWL_TRUSTED_ORIGINS', 'hub.owl.test')
    with pytest.raises(ValueError, match=r"OWL_TRUSTED_ORIGINS: 'hub\.owl\.test' is not an origin"):
        WebServer('test', tmp_path)


def test_pages_starting_together_start_one_front_door(tmp_path):
    folder = tmp_path / 'pages'
    environ = {**os.environ, 'OWL_FRONT_DOOR_PORT': '0'}
    barrier = threading.Barrier(4)

    def start():
        barrier.wait()
        return pages.ensure_front_door(folder, environ)
    try:
        with ThreadPoolExecutor(4) as pool:
            urls = set(pool.map(lambda _: start(), range(4)))
        assert len(urls) == 1
        assert request(urls.pop())[0] == 200
    finally:
        stop_front_door(folder)


def test_a_taken_port_gives_another_and_a_removed_folder_ends_the_front_door(tmp_path):
    folder = tmp_path / 'pages'
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen()
        port = taken.getsockname()[1]
        url = pages.ensure_front_door(folder, {**os.environ, 'OWL_FRONT_DOOR_PORT': str(port)})
    assert url != f'http://127.0.0.1:{port}/'
    pid = pages.front_door_record(folder).pid
    for path in folder.iterdir():
        path.unlink()
    folder.rmdir()
    wait_for(lambda: gone(pid), 'the front door to leave with its folder')


def test_a_page_that_cannot_join_says_why_and_serves_at_its_own_address(tmp_path, monkeypatch):
    folder = tmp_path / 'pages'
    folder.mkdir(mode=0o777)
    folder.chmod(0o777)
    monkeypatch.setenv('OWL_PAGES_DIR', str(folder))
    log = []
    server = WebServer('test', tmp_path, log=log.append)
    server.join_front_door(PAGE, CATALOGUE)
    server.start()
    try:
        assert server.address == server.url
        assert log == [f'not at the front door: the pages folder {folder} is not a private folder of yours '
                       '(mode 0700); remove it, or choose another with OWL_PAGES_DIR '
                       f'(the page is at {server.url})']
    finally:
        server.stop()
    with pytest.raises(ValueError, match="'Test Page' cannot be a page's path"):
        server.join_front_door({**PAGE, 'mount': 'Test Page'}, CATALOGUE)


AS_NOBODY = ['setpriv', '--reuid=nobody', '--regid=nogroup', '--clear-groups', '/usr/bin/python3', '-c']
# What another account's process sees of a page: each request's status and first line, raw HTTP.
PEEK = '''
import json, socket, sys
from urllib.parse import urlsplit
for url, path, upgrade in json.loads(sys.argv[1]):
    parts = urlsplit(url)
    with socket.create_connection((parts.hostname, parts.port), timeout=10) as connection:
        extra = ('Upgrade: websocket\\r\\nConnection: Upgrade\\r\\nSec-WebSocket-Version: 13\\r\\n'
                 'Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\\r\\n') if upgrade else ''
        connection.sendall(f'GET {path} HTTP/1.1\\r\\nHost: {parts.netloc}\\r\\n{extra}\\r\\n'.encode())
        answer = b''
        while b'\\r\\n\\r\\n' not in answer:  # an opened WebSocket would stay open: read what is due
            answer += connection.recv(65536)
        head, _, body = answer.partition(b'\\r\\n\\r\\n')
        length = [int(line.split(b':')[1]) for line in head.split(b'\\r\\n')
                  if line.lower().startswith(b'content-length:')]
        while len(body) < (length or [0])[0]:
            body += connection.recv(65536)
    text = body.decode()
    print(head.split()[1].decode(), json.loads(text).get('error', '') if text.startswith('{') else text[:40])
'''


def test_owner_only_pages_serve_their_own_account_and_refuse_another(tmp_path, monkeypatch):
    if os.geteuid() != 0:
        pytest.skip('acting as another account needs root (CI runs as root)')
    monkeypatch.setenv('OWL_PAGES_OWNER_ONLY', '1')  # as a class server sets it for each student
    page = JoinedPage(tmp_path, monkeypatch)
    try:
        assert request(page.door, 'POST', '/test-page/api/echo', b'{}')[0] == 201  # this account's own
        assert request(page.server.url, 'POST', '/api/echo', b'{}')[0] == 201
        assert run(open_socket(page.door)) == 'open'
        tries = [(page.door, '/', False), (page.door, '/test-page/api/echo', False),
                 (page.door, '/test-page/ws', True), (page.server.url, '/', False),
                 (page.server.url, '/ws', True)]
        peek = subprocess.run([*AS_NOBODY, PEEK, json.dumps(tries)], capture_output=True, text=True,
                              check=False, timeout=30)
        answers = peek.stdout.splitlines()
        assert len(answers) == len(tries), peek.stderr
        for answer in answers:
            assert answer.startswith(f'403 refused: these pages are for account uid {os.getuid()} only '
                                     '(OWL_PAGES_OWNER_ONLY=1) and account uid '), answer
        assert len(page.seen) == 2  # this account's two requests; nothing of the other's
    finally:
        page.close()
