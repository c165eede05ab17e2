"""The pages' server over real sockets on 127.0.0.1 (no ROS): files, routes, the WebSocket, bad input."""

import asyncio
import http.client
import json
import socket
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import aiohttp
import pytest
from owl_web import codec
from owl_web.codec import ApiError
from owl_web.origins import foreign_request
from owl_web.server import Connection, Subscription, WebServer


@pytest.fixture
def web(tmp_path, monkeypatch):
    """A server with a page, a fake npm library, routes and channels; yields (server, log lines, closed)."""
    static = tmp_path / 'page'
    static.mkdir()
    (static / 'index.html').write_text('<!DOCTYPE html><title>test page</title>')
    (static / 'app.js').write_text('// the page')
    (tmp_path / 'web' / 'node_modules' / 'plotlib' / 'dist').mkdir(parents=True)
    (tmp_path / 'web' / 'package.json').write_text(json.dumps({'dependencies': {'plotlib': '1.2.3'}}))
    (tmp_path / 'web' / 'node_modules' / 'plotlib' / 'package.json').write_text('{}')
    (tmp_path / 'web' / 'node_modules' / 'plotlib' / 'dist' / 'plot.js').write_text('// plotlib')
    (tmp_path / 'web' / 'secret.js').write_text('// not a library')
    monkeypatch.setenv('OWL_ROOT', str(tmp_path))
    log: list[str] = []
    closed: list[object] = []
    commands: list[object] = []
    server = WebServer('test', static, log=log.append)
    server.commands_run = commands  # what the 'turn' command was given, for the tests

    def echo(request):
        return 201, {'params': request.params, 'query': request.query, 'body': request.json()}

    def broken(request):
        raise RuntimeError('no such thing\nsecond line')

    def refuse(request):
        raise ApiError(400, 'rate must be a number of Hz')

    def open_counter(subscription):
        codec.check_keys(subscription.params, ('start',))
        start = subscription.params.get('start', 0)
        if start < 0:
            raise ApiError(400, f'start must not be negative, got {start}')
        # pushed from another thread, as a ROS callback would
        threading.Thread(target=lambda: [subscription.send({'n': start + n}) for n in range(3)]).start()

    def open_frames(subscription):
        subscription.send_binary({'content_type': 'image/jpeg', 'frame': 1}, b'\xff\xd8\xff fake jpeg')
        subscription.error('frame 2 cannot be shown')

    def turn(arguments):
        codec.check_keys(arguments, ('orientation',), required=('orientation',))
        commands.append(codec.unit_quaternion(arguments['orientation']))

    server.command('turn', turn)
    # the thread each runs in: where_turn's a handler thread, where_nudge's (at_once) the server's
    server.command('where_turn', lambda _: {'thread': threading.current_thread().name})
    server.command('where_nudge', lambda _: {'thread': threading.current_thread().name}, at_once=True)
    server.route('POST', '/api/echo/{name}', echo)
    server.route('GET', '/api/broken', broken)
    server.route('GET', '/api/refuse', refuse)
    server.channel('counter', open_counter, closed.append)
    server.channel('frames', open_frames)
    server.start()
    try:
        yield server, log, closed
    finally:
        server.stop()


def run(coroutine):
    """The coroutine's result, from an event loop in a thread of its own.

    The main thread may have one running already: a browser test's Playwright in the same session.
    """
    with ThreadPoolExecutor(1) as thread:
        return thread.submit(asyncio.run, asyncio.wait_for(coroutine, 30)).result()


def fetch(server, method, path, body=None):
    """(status, content type, body); the path goes as it is (no client tidies a '..' away)."""
    host, port = server.url.removeprefix('http://').rstrip('/').split(':')
    connection = http.client.HTTPConnection(host, int(port), timeout=30)
    try:
        connection.request(method, path, body=body)
        response = connection.getresponse()
        return response.status, response.getheader('Content-Type', ''), response.read()
    finally:
        connection.close()


def error_line(answer):
    status, content_type, body = answer
    data = json.loads(body)
    assert content_type.startswith('application/json'), body
    assert list(data) == ['error'], body
    assert '\n' not in data['error']
    return status, data['error']


def test_files_libraries_and_nothing_else(web):
    server, _, _ = web
    assert server.url.startswith('http://127.0.0.1:')
    assert server.missing_libraries() is None
    status, content_type, body = fetch(server, 'GET', '/')
    assert (status, content_type) == (200, 'text/html; charset=utf-8')
    assert body == b'<!DOCTYPE html><title>test page</title>'
    assert fetch(server, 'GET', '/static/app.js')[:2] == (200, 'text/javascript; charset=utf-8')
    assert b'OwlSocket' in fetch(server, 'GET', '/owl/socket.js')[2]
    assert fetch(server, 'GET', '/lib/plotlib/dist/plot.js')[2] == b'// plotlib'
    for path in ('/static/../index.html', '/lib/plotlib/../../secret.js', '/lib/plotlib/package.json',
                 '/lib/other/dist/plot.js', '/static/.hidden.js', '/owl/', '/nothing.html'):
        status, line = error_line(fetch(server, 'GET', path))
        assert status == 404, (path, line)
        assert line.startswith("no page '"), (path, line)


def test_missing_libraries_are_named(tmp_path, monkeypatch):
    (tmp_path / 'web').mkdir()
    (tmp_path / 'web' / 'package.json').write_text(json.dumps({'dependencies': {'elkjs': '0.12.1'}}))
    monkeypatch.setenv('OWL_ROOT', str(tmp_path))
    server = WebServer('test', tmp_path)
    try:
        assert server.missing_libraries() == \
            "the pages' libraries (elkjs) are not installed: run 'make setup'"
    finally:
        server.stop()
    monkeypatch.delenv('OWL_ROOT')
    server = WebServer('test', tmp_path)
    try:
        assert server.missing_libraries().startswith('OWL_ROOT is not set')
    finally:
        server.stop()


def test_loopback_only_and_busy_ports(tmp_path, monkeypatch):
    for host in ('0.0.0.0', '192.168.1.5', '10.42.0.8'):
        with pytest.raises(ValueError, match=rf'loopback addresses only \(127.x.y.z\), not {host}$'):
            WebServer('test', tmp_path, host=host)
    with socket.socket() as taken:
        taken.bind(('127.0.0.1', 0))
        taken.listen()
        with pytest.raises(OSError, match='Address already in use'):
            WebServer('test', tmp_path, port=taken.getsockname()[1])
        monkeypatch.setenv('OWL_PAGE_PORT_FALLBACK', '1')  # a class server: another student's page has it
        given_way = WebServer('test', tmp_path, port=taken.getsockname()[1])
        try:
            assert given_way.url != f'http://127.0.0.1:{taken.getsockname()[1]}/'
        finally:
            given_way.stop()
    module = WebServer('test', tmp_path, host='127.42.0.8')  # a module's own address, no set-up
    try:
        assert module.url.startswith('http://127.42.0.8:')
    finally:
        module.stop()


def test_routes_and_their_errors(web):
    server, log, _ = web
    status, _, body = fetch(server, 'POST', '/api/echo/imu?x=1&x=2', body=b'{"kp": 2.5}')
    assert (status, json.loads(body)) == (201, {'params': {'name': 'imu'}, 'query': {'x': '2'},
                                                'body': {'kp': 2.5}})
    assert error_line(fetch(server, 'POST', '/api/echo/imu', body=b'{"kp": ')) == \
        (400, 'malformed JSON in the request body: Expecting value (line 1, column 8)')
    assert error_line(fetch(server, 'GET', '/api/refuse')) == (400, 'rate must be a number of Hz')
    assert error_line(fetch(server, 'GET', '/api/echo/imu')) == (405, 'GET is not allowed on /api/echo/imu')
    assert error_line(fetch(server, 'GET', '/api/ecco')) == \
        (404, "no API path '/api/ecco'; known: /api/broken, /api/echo/{name}, /api/refuse")
    assert error_line(fetch(server, 'GET', '/api/broken')) == \
        (500, 'internal error: no such thing')
    assert log == ['GET /api/broken: no such thing']
    status, line = error_line(fetch(server, 'POST', '/api/echo/imu', body=b'x' * (codec.MAX_BODY + 1)))
    assert (status, line) == (413, 'request body of 1048577 bytes is over the limit of 1048576')
    assert fetch(server, 'POST', '/api/echo/imu', body=b'{}')[0] == 201  # still serving


async def exchange(server, *messages, receive=1):
    """Send messages on one WebSocket; return what came back and the close code (None while open).

    Frames come back as (header, payload).
    """
    received = []
    async with aiohttp.ClientSession() as session, session.ws_connect(server.url + 'ws') as socket_:
        for message in messages:
            if isinstance(message, bytes):
                await socket_.send_bytes(message)
            else:
                await socket_.send_str(message if isinstance(message, str) else json.dumps(message))
        while len(received) < receive:
            answer = await socket_.receive(10)
            if answer.type == aiohttp.WSMsgType.TEXT:
                received.append(json.loads(answer.data))
            elif answer.type == aiohttp.WSMsgType.BINARY:
                received.append(codec.unpack_frame(answer.data))
            else:
                break
        return received, socket_.close_code


def test_subscriptions_push_updates_frames_and_errors(web):
    server, _, closed = web
    received, _ = run(exchange(server, {'type': 'subscribe', 'id': 'c', 'channel': 'counter', 'start': 10},
                               receive=1))
    # updates are state: a newer one may replace one not sent yet, never reorder
    numbers = [message['data']['n'] for message in received]
    assert numbers
    assert numbers == sorted(numbers)
    assert set(numbers) <= {10, 11, 12}
    assert received[0]['type'] == 'update'
    assert received[0]['id'] == 'c'
    wait_for(lambda: len(closed) == 1, 'the channel to hear the page left')
    received, _ = run(exchange(server, {'type': 'subscribe', 'id': 7, 'channel': 'frames'}, receive=2))
    assert {'type': 'error', 'id': 7, 'error': 'frame 2 cannot be shown'} in received
    [(header, payload)] = [message for message in received if isinstance(message, tuple)]
    assert header == {'type': 'update', 'id': 7, 'data': {'content_type': 'image/jpeg', 'frame': 1}}
    assert payload == b'\xff\xd8\xff fake jpeg'


def test_unsubscribe_stops_the_channel(web):
    server, _, closed = web

    async def subscribe_then_unsubscribe():
        async with aiohttp.ClientSession() as session, session.ws_connect(server.url + 'ws') as socket_:
            await socket_.send_json({'type': 'subscribe', 'id': 1, 'channel': 'counter'})
            await socket_.receive(10)
            await socket_.send_json({'type': 'unsubscribe', 'id': 1})
            await asyncio.sleep(0.3)
            count = len(closed)
            await socket_.send_json({'type': 'unsubscribe', 'id': 1})
            while (again := json.loads((await socket_.receive(10)).data))['type'] == 'update':
                pass  # what was sent before the unsubscribe
            return count, again
    count, again = run(subscribe_then_unsubscribe())
    assert count == 1
    assert again == {'type': 'error', 'id': 1, 'error': 'no subscription 1'}


@pytest.mark.parametrize(('message', 'error'), [
    ('{"type": "subscribe", ', 'malformed JSON in the message: Expecting property name enclosed in double '
                               'quotes (line 1, column 23)'),
    ('[1, 2]', 'the message must be a JSON object, got list'),
    ({'id': 1, 'channel': 'counter'}, 'the message needs a "type" string, got null'),
    ({'type': 'subscrbe', 'id': 1}, 'unknown message type "subscrbe" (did you mean \'subscribe\'?); '
                                    'expected: subscribe, unsubscribe, command'),
    ({'type': 'command', 'id': 2}, "missing key 'name' in the command message"),
    ({'type': 'command', 'id': 2, 'name': 'trun'},
     'unknown command "trun" (did you mean \'turn\'?); known: turn, where_nudge, where_turn'),
    ({'type': 'command', 'id': 2, 'name': 'turn', 'orientation': {'x': 0, 'y': 0, 'z': 0, 'w': 'nan'}},
     'the orientation: "w" must be a number, got "nan"'),
    ('{"type": "command", "id": 2, "name": "turn", "orientation": {"x": NaN, "y": 0, "z": 0, "w": 1}}',
     'the orientation: "x" must be finite, got nan'),
    ({'type': 'command', 'id': 2, 'name': 'turn', 'orientation': {'x': 0, 'y': 0, 'z': 0, 'w': 2}},
     'the orientation must be a unit quaternion (norm 1), got norm 2'),
    ({'type': 'command', 'id': 2, 'name': 'turn', 'orient': {}},
     "unknown key 'orient' (did you mean 'orientation'?); expected: orientation"),
    ({'type': 'subscribe', 'channel': 'counter'}, "missing key 'id' in the subscribe message"),
    ({'type': 'subscribe', 'id': 1, 'channel': 'countr'},
     'unknown channel "countr" (did you mean \'counter\'?); known: counter, frames'),
    ({'type': 'subscribe', 'id': 1, 'channel': 'counter', 'strat': 1},
     "unknown key 'strat' (did you mean 'start'?); expected: start"),
    ({'type': 'subscribe', 'id': 1, 'channel': 'counter', 'start': -1}, 'start must not be negative, got -1'),
    ({'type': 'subscribe', 'id': [1], 'channel': 'counter'},
     '"id" must be a number or a string of 1 to 64 characters, got [1]'),
    ({'type': 'unsubscribe'}, "missing key 'id'"),
    (b'\x00\x01', 'binary messages are not accepted: send JSON text'),
    ('{"type": "subscribe", "pad": "' + 'x' * 70000 + '"}',
     'message of 70032 bytes is over the limit of 65536'),
])
def test_bad_messages_get_one_line_and_the_connection_lives_on(web, message, error):
    server, _, _ = web
    then = {'type': 'subscribe', 'id': 'ok', 'channel': 'counter'}
    received, close_code = run(exchange(server, message, then, receive=2))
    assert received[0]['type'] == 'error', received[0]
    assert received[0]['error'] == error, received[0]
    assert '\n' not in received[0]['error']
    assert received[1]['type'] == 'update'
    assert received[1]['id'] == 'ok'  # the same connection still works
    assert close_code is None


def test_commands_are_carried_out_and_answered(web):
    server, _, _ = web
    command = {'type': 'command', 'id': 'c1', 'name': 'turn', 'orientation': {'x': 0, 'y': 0, 'z': 1, 'w': 0}}
    received, _ = run(exchange(server, command, receive=1))
    assert received == [{'type': 'done', 'id': 'c1'}]
    assert server.commands_run == [(0.0, 0.0, 1.0, 0.0)]


def test_a_command_at_once_runs_in_the_servers_thread_the_others_in_their_own(web):
    server, _, _ = web
    received, _ = run(exchange(server, {'type': 'command', 'id': 1, 'name': 'where_nudge'},
                               {'type': 'command', 'id': 2, 'name': 'where_turn'}, receive=2))
    assert received == [{'type': 'done', 'id': 1, 'result': {'thread': 'test web'}},
                        {'type': 'done', 'id': 2, 'result': {'thread': 'test handler'}}]


def test_a_bad_command_reaches_no_handler(web):
    server, _, _ = web
    bad = {'type': 'command', 'id': 3, 'name': 'turn', 'orientation': {'x': 1, 'y': 1, 'z': 1, 'w': 1}}
    received, _ = run(exchange(server, bad, receive=1))
    assert received == [{'type': 'error', 'id': 3,
                         'error': 'the orientation must be a unit quaternion (norm 1), got norm 2'}]
    assert server.commands_run == []


def test_a_second_subscription_with_the_same_id_is_refused(web):
    server, _, _ = web
    first = {'type': 'subscribe', 'id': 1, 'channel': 'frames'}
    received, _ = run(exchange(server, first, first, receive=3))
    assert {'type': 'error', 'id': 1, 'error': 'subscription id 1 is already in use'} in received


def test_a_huge_message_closes_only_its_connection(web):
    server, log, _ = web
    huge = '{"type": "subscribe", "pad": "' + 'x' * (codec.MAX_BODY + 10) + '"}'
    received, close_code = run(exchange(server, huge, receive=1))
    # "message too big"; or, when the kernel resets the connection (the rest of the message is never
    # read) before the client reads the close frame, an abnormal closure
    assert received == []
    assert close_code in (aiohttp.WSCloseCode.MESSAGE_TOO_BIG,
                          aiohttp.WSCloseCode.ABNORMAL_CLOSURE)
    # the client may see the close before the server's handler has read the error and logged it
    wait_for(lambda: log, 'the log line')
    assert len(log) == 1
    assert log[0].startswith('closed a WebSocket connection: ')
    assert '\n' not in log[0]
    received, _ = run(exchange(server, {'type': 'subscribe', 'id': 1, 'channel': 'frames'}, receive=1))
    assert received  # the server serves the next page


def test_stop_tells_pages_the_server_is_going_away(web):
    server, _, _ = web

    async def watch():
        async with aiohttp.ClientSession() as session, session.ws_connect(server.url + 'ws') as socket_:
            await socket_.send_json({'type': 'subscribe', 'id': 1, 'channel': 'frames'})
            await socket_.receive(10)
            threading.Thread(target=server.stop).start()
            while (await socket_.receive(10)).type not in (aiohttp.WSMsgType.CLOSE, aiohttp.WSMsgType.CLOSED):
                pass
            return socket_.close_code
    assert run(watch()) == aiohttp.WSCloseCode.GOING_AWAY


def wait_for(condition, what, timeout=10.0):
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, f'timed out waiting for {what}'
        time.sleep(0.02)


def test_malformed_http_gets_400_and_at_most_a_line(web, capfd):
    server, log, _ = web
    host, port = server.url.removeprefix('http://').rstrip('/').split(':')
    for raw in (b'GARBAGE\r\n\r\n', b'GET / HTTP/1.1\r\nContent-Length: abc\r\n\r\n',
                b'\x16\x03\x01\x00\xa5\x01\x00\x00',  # a TLS hello on the plain port
                b'GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\r\n',
                b'POST /api/echo/x HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n'):
        with socket.create_connection((host, int(port)), timeout=10) as connection:
            connection.sendall(raw)
            assert connection.recv(100).split(b'\r\n')[0].endswith(b' 400 Bad Request'), raw
    assert log == ['Error handling request from 127.0.0.1: Invalid character in Content-Length',
                   'Error handling request from 127.0.0.1: Invalid character in chunk size']
    captured = capfd.readouterr()
    assert 'Traceback' not in captured.out + captured.err
    assert fetch(server, 'GET', '/')[0] == 200  # still serving


def test_only_this_machines_pages_may_use_the_server(web):
    server, _, _ = web
    assert foreign_request('127.0.0.1:8090', None) is None
    assert foreign_request('localhost:9000', 'http://localhost:9000') is None  # e.g. through ssh -L
    assert foreign_request('127.42.0.8:80', 'http://127.42.0.8') is None
    assert foreign_request('[::1]:8090', 'http://[::1]:8090') is None
    assert foreign_request('evil.example:8090', None) == \
        "refused: Host 'evil.example:8090' is not a loopback address or a trusted origin's"
    assert foreign_request('127.0.0.1:8090', 'https://evil.example') == \
        'refused: a page of https://evil.example may not use this server'
    assert foreign_request('127.0.0.1:8090', 'null') == 'refused: a page of null may not use this server'
    # over the wire: another site's page can neither post nor open the WebSocket; the server's own can
    host, port = server.url.removeprefix('http://').rstrip('/').split(':')
    for headers in ({'Origin': 'https://evil.example'}, {'Host': 'rebound.example'}):
        connection = http.client.HTTPConnection(host, int(port), timeout=10)
        connection.request('POST', '/api/echo/imu', body=b'{}', headers=headers)
        response = connection.getresponse()
        assert response.status == 403
        assert json.loads(response.read())['error'].startswith('refused: ')
        connection.close()

    async def open_socket(origin):
        async with aiohttp.ClientSession() as session:
            try:
                async with session.ws_connect(server.url + 'ws', origin=origin):
                    return 'open'
            except aiohttp.WSServerHandshakeError as error:
                return error.status
    assert run(open_socket('https://evil.example')) == 403
    assert run(open_socket(server.url.rstrip('/'))) == 'open'
    connection = http.client.HTTPConnection(host, int(port), timeout=10)
    connection.request('POST', '/api/echo/imu', body=b'{}', headers={'Origin': server.url.rstrip('/')})
    assert connection.getresponse().status == 201
    connection.close()


def test_pages_get_no_compression_even_when_they_ask_for_it(web):
    server, _, _ = web

    async def negotiated():
        async with aiohttp.ClientSession() as session, \
                session.ws_connect(server.url + 'ws', compress=15) as socket_:
            return socket_.compress, socket_._response.headers.get('Sec-WebSocket-Extensions')

    compress, extensions = run(negotiated())
    assert compress == 0
    assert extensions is None


class CountingLoop:
    """Stands in for the event loop: counts the wake-ups a connection asks for."""

    def __init__(self):
        self.wakeups = 0

    def call_soon_threadsafe(self, callback):
        self.wakeups += 1


def test_a_burst_of_updates_wakes_the_sender_once_and_the_next_burst_once_more():
    async def burst_then_send():
        connection = Connection(None, asyncio.get_running_loop())
        loop = CountingLoop()
        connection.loop = loop
        subscription = Subscription(connection, 1, 'kit', {})
        connection.subscriptions[1] = subscription
        for number in range(100):
            connection.offer(subscription, f'state {number}')
        connection.error(1, 'one error line')
        first = loop.wakeups
        sent = []

        class Page:
            async def send_str(self, message):
                sent.append(message)
                if len(sent) == 2:  # all that was queued went in one batch
                    raise ConnectionError

        connection.websocket = Page()
        connection._wake.set()  # the wake-up the counting loop swallowed
        await connection.send_pending()
        connection.offer(subscription, 'state 100')
        return first, loop.wakeups, sent

    first, after_next, sent = run(burst_then_send())
    assert first == 1
    assert after_next == 2
    assert sent[1] == 'state 99'


def test_a_subscription_says_whether_an_update_still_waits_to_be_sent():
    async def offer_then_send():
        connection = Connection(None, asyncio.get_running_loop())
        connection.loop = CountingLoop()
        plots, kit = Subscription(connection, 1, 'plots', {}), Subscription(connection, 2, 'kit', {})
        connection.subscriptions.update({1: plots, 2: kit})
        before = plots.pending()
        connection.offer(plots, 'batch 1')
        waiting = (plots.pending(), kit.pending())

        class Page:
            async def send_str(self, message):
                raise ConnectionError  # the batch was taken off the queue to be sent

        connection.websocket = Page()
        connection._wake.set()
        await connection.send_pending()
        return before, waiting, plots.pending()

    assert run(offer_then_send()) == (False, (True, False), False)


# Run in a process of its own: this one has imported aiohttp already.
LAZY_START = """
import sys, time, urllib.request
from pathlib import Path
from owl_web.server import WebServer

folder = Path(sys.argv[1])
(folder / 'index.html').write_text('<!DOCTYPE html><title>lazy</title>')
server = WebServer('lazy', folder)
server.start()
time.sleep(0.3)  # a page nobody opens: the server's thread only waits
print('aiohttp before the first request:', 'aiohttp' in sys.modules)
with urllib.request.urlopen(server.url, timeout=10) as answer:
    print('first request:', answer.status, b'<title>lazy</title>' in answer.read())
print('aiohttp after it:', 'aiohttp' in sys.modules)
server.stop()
unopened = WebServer('unopened', folder)
unopened.start()
started = time.monotonic()
unopened.stop()
print('a stop before any request in under a second:', time.monotonic() - started < 1.0)
"""


def test_aiohttp_is_set_up_at_the_first_request_and_a_page_never_opened_stops_at_once(tmp_path):
    import subprocess
    import sys

    done = subprocess.run([sys.executable, '-c', LAZY_START, str(tmp_path)], capture_output=True, text=True,
                          timeout=60, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        'aiohttp before the first request: False',
        'first request: 200 True',
        'aiohttp after it: True',
        'a stop before any request in under a second: True',
    ], done.stderr
