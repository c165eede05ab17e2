"""Forwarding a browser's request, or its WebSocket, to a page's own server (the front door's half).

The page's server sees a request from this machine to its own address: Host is its own, an Origin
becomes its own origin (the front door has checked the browser's before), cookies and
authorization stay behind (our pages use neither; a class server's login cookie is not theirs to
see), and nothing of the hop itself (Connection, Upgrade, ...) passes. Bodies stream both ways.

A WebSocket that opens a connection of its own (browsers do) is passed through as bytes once its
request is rewritten (FirstRequest, RawPipe): the page and its server then talk as if directly,
handshake, extensions and close codes included, and the front door never parses a frame. Parsing
and re-sending each message cost the front door 3.6 % of a core on the robot view's stream (about
280 messages a second). A WebSocket request that comes on a connection already used for HTTP is
passed on message for message instead (Forwarder.websocket).
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import cast
from urllib.parse import urlsplit

import aiohttp
from aiohttp import WSMsgType, web
from multidict import CIMultiDict

from owl_web import codec

# Headers of one hop (RFC 9110 section 7.6.1) and those the front door sets itself.
NOT_FORWARDED = frozenset({
    'connection', 'keep-alive', 'proxy-authenticate', 'proxy-authorization', 'proxy-connection', 'te',
    'trailer', 'transfer-encoding', 'upgrade', 'host', 'origin', 'cookie', 'authorization',
    'content-length', 'forwarded', 'x-forwarded-for', 'x-forwarded-host', 'x-forwarded-proto',
    'x-forwarded-prefix', 'sec-websocket-key', 'sec-websocket-version', 'sec-websocket-extensions',
    'sec-websocket-accept'})
NOT_RETURNED = frozenset({'connection', 'keep-alive', 'transfer-encoding', 'content-length', 'set-cookie',
                          'upgrade', 'trailer'})
CONNECT_TIMEOUT = 3.0  # s for a page's server to accept; it is on this machine
CHUNK = 1 << 16
# A page's server closes a page's WebSocket that sends more (codec.MAX_BODY); the front door reads
# up to that much so the server says it, and more from the server (a camera frame is far less).
FROM_SERVER_LIMIT = 16 << 20
# The page's side of a forwarded WebSocket, or the server's.
EitherSocket = web.WebSocketResponse[bool] | aiohttp.ClientWebSocketResponse[bool]
# Close codes a WebSocket may not send (1005, 1006: "no code", "abnormal"): what the page sees instead.
GONE = 1001


class BackendAway(Exception):
    """The page's server did not accept the connection: it stopped, or is starting again."""


def own_origin(base_url: str) -> str:
    """http://host:port of a server's base URL."""
    parts = urlsplit(base_url)
    return f'{parts.scheme}://{parts.netloc}'


def forwarded_headers(headers: Mapping[str, str], base_url: str, upgrade: bool = False) -> dict[str, str]:
    """A request's headers as the page's server gets them (see the module's docstring).

    With upgrade, the WebSocket handshake's own headers pass too (the bytes that follow are the page's).
    """
    keep = UPGRADE_HEADERS if upgrade else frozenset()
    forwarded = {name: value for name, value in headers.items()
                 if name.lower() not in NOT_FORWARDED or name.lower() in keep}
    if 'Origin' in headers:
        forwarded['Origin'] = own_origin(base_url)
    return forwarded


# ---- a WebSocket's own connection, passed through as bytes ----------------------------------------

UPGRADE_HEADERS = frozenset({'connection', 'upgrade', 'sec-websocket-key', 'sec-websocket-version',
                             'sec-websocket-extensions', 'sec-websocket-protocol'})
MAX_HEAD = 64 << 10  # bytes of a request's head the first look reads; longer ones are aiohttp's to refuse


@dataclass(frozen=True)
class RequestHead:
    """The request line and headers of a connection's first request, as the first look read them."""

    method: str
    target: str
    headers: CIMultiDict[str]

    @classmethod
    def parse(cls, head: bytes) -> RequestHead | None:
        """The head (without its blank line), or None when it is not a plain HTTP/1.1 request's."""
        lines = head.decode('latin-1').split('\r\n')
        parts = lines[0].split(' ')
        if len(parts) != 3 or parts[2] != 'HTTP/1.1':
            return None
        headers: CIMultiDict[str] = CIMultiDict()
        for line in lines[1:]:
            name, colon, value = line.partition(':')
            if not colon or not name or name != name.strip():
                return None
            headers.add(name, value.strip())
        return cls(parts[0], parts[1], headers)

    @property
    def opens_websocket(self) -> bool:
        """Whether the request asks to become a WebSocket (GET with Upgrade: websocket)."""
        return (self.method == 'GET' and self.headers.get('Upgrade', '').lower() == 'websocket'
                and 'upgrade' in self.headers.get('Connection', '').lower())


def rewritten_head(head: RequestHead, base_url: str, target: str) -> bytes:
    """The head the page's server gets for a WebSocket at target (its path and query on that server)."""
    headers = forwarded_headers(head.headers, base_url, upgrade=True)
    lines = [f'GET {target} HTTP/1.1', f'Host: {urlsplit(base_url).netloc}',
             *(f'{name}: {value}' for name, value in headers.items())]
    return ('\r\n'.join(lines) + '\r\n\r\n').encode('latin-1')


class RawPipe(asyncio.Protocol):
    """Bytes arriving on one connection go out on its peer's, as they come; either end closes both.

    A peer that cannot keep up (its buffer full) pauses the reading of this connection until it drains.
    """

    def __init__(self, peer: asyncio.Transport | None = None) -> None:
        self.peer = peer
        self.transport: asyncio.Transport | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        """Keep the connection this pipe reads (a browser's, or a page server's)."""
        self.transport = cast(asyncio.Transport, transport)  # uvloop's are not asyncio's subclasses

    def data_received(self, data: bytes) -> None:
        """Send the bytes on."""
        if self.peer is not None:
            self.peer.write(data)

    def eof_received(self) -> bool | None:
        """The other end is done: so is the peer."""
        if self.peer is not None:
            self.peer.close()
        return None

    def connection_lost(self, exc: Exception | None) -> None:
        """Gone: close the peer too."""
        if self.peer is not None:
            self.peer.close()

    def pause_writing(self) -> None:
        """This connection's buffer is full: stop reading what would go into it."""
        if self.peer is not None:
            self.peer.pause_reading()

    def resume_writing(self) -> None:
        """Drained: read again."""
        if self.peer is not None:
            self.peer.resume_reading()


# The WebSocket's page server and the head it gets, or None for aiohttp to answer the request.
WebSocketTarget = Callable[[RequestHead, asyncio.Transport], 'tuple[str, bytes] | None']


class FirstRequest(asyncio.Protocol):
    """A new connection's first look: a WebSocket for a page is passed through, anything else goes to aiohttp.

    http is aiohttp's protocol factory (AppRunner.server); target says where a WebSocket goes.
    """

    def __init__(self, http: Callable[[], asyncio.Protocol], target: WebSocketTarget,
                 relays: set[asyncio.Transport]) -> None:
        self.http = http
        self.target = target
        self.relays = relays
        self.transport: asyncio.Transport | None = None
        self.buffer = b''
        self.passing: asyncio.Future[None] | None = None

    def connection_made(self, transport: asyncio.BaseTransport) -> None:
        """Start looking at what the browser sends."""
        self.transport = cast(asyncio.Transport, transport)  # uvloop's are not asyncio's subclasses

    def data_received(self, data: bytes) -> None:
        """Read until the first request's head is whole, then decide."""
        self.buffer += data
        end = self.buffer.find(b'\r\n\r\n')
        if end < 0:
            if len(self.buffer) > MAX_HEAD:
                self.hand_over()
            return
        head = RequestHead.parse(self.buffer[:end])
        assert self.transport is not None
        found = self.target(head, self.transport) if head is not None and head.opens_websocket else None
        if found is None:
            self.hand_over()
            return
        self.transport.pause_reading()
        self.passing = asyncio.ensure_future(self.pass_through(*found, self.buffer[end + 4:]))

    def hand_over(self) -> None:
        """Let aiohttp serve this connection from its first byte."""
        assert self.transport is not None
        protocol = self.http()
        self.transport.set_protocol(protocol)
        protocol.connection_made(self.transport)
        if self.buffer:
            protocol.data_received(self.buffer)
        self.transport.resume_reading()

    async def pass_through(self, base_url: str, head: bytes, rest: bytes) -> None:
        """Connect to the page's server and pipe both ways; aiohttp says why when it does not accept."""
        assert self.transport is not None
        parts = urlsplit(base_url)
        loop = asyncio.get_running_loop()
        try:
            server, _ = await asyncio.wait_for(loop.create_connection(
                lambda: RawPipe(self.transport), parts.hostname or '127.0.0.1', parts.port or 80),
                CONNECT_TIMEOUT)
        except (OSError, asyncio.TimeoutError):
            self.hand_over()
            return
        if self.transport.is_closing():
            server.close()
            return
        self.transport.set_protocol(RawPipe(server))
        self.relays.update((self.transport, server))
        server.write(head + rest)
        self.transport.resume_reading()

    def connection_lost(self, exc: Exception | None) -> None:
        """The browser left before its first request was whole."""


class Forwarder:
    """One HTTP client session for every forwarded request and WebSocket of a front door."""

    def __init__(self) -> None:
        self._session: aiohttp.ClientSession | None = None

    @property
    def session(self) -> aiohttp.ClientSession:
        """The client session, made on first use inside the running event loop."""
        if self._session is None:
            self._session = aiohttp.ClientSession(
                auto_decompress=False, cookie_jar=aiohttp.DummyCookieJar(),
                timeout=aiohttp.ClientTimeout(total=None, connect=CONNECT_TIMEOUT))
        return self._session

    async def close(self) -> None:
        """Close the session (the front door is stopping)."""
        if self._session is not None:
            await self._session.close()
            self._session = None

    async def http(self, request: web.Request, base_url: str, rest: str,
                   extra_headers: dict[str, str]) -> web.StreamResponse:
        """Forward request to base_url + rest (the path below the page's mount, and its query).

        The answer streams back with extra_headers added; BackendAway when the server does not accept.
        """
        target = base_url.rstrip('/') + rest
        try:
            upstream = await self.session.request(
                request.method, target, headers=forwarded_headers(request.headers, base_url),
                data=request.content if request.body_exists else None, allow_redirects=False)
        except (aiohttp.ClientConnectionError, asyncio.TimeoutError) as error:
            raise BackendAway(codec.one_line(error)) from None
        async with upstream:
            headers = {name: value for name, value in upstream.headers.items()
                       if name.lower() not in NOT_RETURNED}
            response = web.StreamResponse(status=upstream.status, reason=upstream.reason,
                                          headers={**headers, **extra_headers})
            if upstream.content_length is not None:
                response.content_length = upstream.content_length
            await response.prepare(request)
            async for chunk in upstream.content.iter_chunked(CHUNK):
                await response.write(chunk)
            await response.write_eof()
            return response

    async def websocket(self, request: web.Request, base_url: str, rest: str,
                        away_reason: str) -> web.WebSocketResponse:
        """Pass a page's WebSocket through to its server's, message for message, until either closes.

        A server that does not accept gets the page's socket closed with away_reason (the page says
        it; our pages' sockets try again by themselves).
        """
        # No permessage-deflate: most of what streams is JPEG, which deflate cannot shrink (with it the
        # front door spent 6 % of a core on the robot view's stream instead of 2).
        page = web.WebSocketResponse(max_msg_size=codec.MAX_BODY, autoping=True, compress=False)
        await page.prepare(request)
        target = base_url.rstrip('/').replace('http', 'ws', 1) + rest
        try:
            server = await self.session.ws_connect(
                target, headers=forwarded_headers(request.headers, base_url), max_msg_size=FROM_SERVER_LIMIT,
                autoping=True)
        except (aiohttp.ClientError, asyncio.TimeoutError):
            await page.close(code=aiohttp.WSCloseCode.TRY_AGAIN_LATER, message=away_reason.encode()[:120])
            return page
        to_server = asyncio.ensure_future(_pass_on(page, server))
        to_page = asyncio.ensure_future(_pass_on(server, page))
        ending: tuple[int | None, str] = (None, '')
        try:
            done, _ = await asyncio.wait({to_server, to_page}, return_when=asyncio.FIRST_COMPLETED)
            ending = next(iter(done)).result()
        finally:
            for task in (to_server, to_page):
                task.cancel()
            for side in (server, page):
                await _close(side, *ending)
        return page


async def _pass_on(source: EitherSocket,
                   sink: EitherSocket) -> tuple[int | None, str]:
    """Send on what source sends until it closes; its close code and reason."""
    while True:
        message = await source.receive()
        if message.type == WSMsgType.TEXT:
            await sink.send_str(message.data)
        elif message.type == WSMsgType.BINARY:
            await sink.send_bytes(message.data)
        elif message.type == WSMsgType.CLOSE:
            return message.data, message.extra or ''
        else:  # closing, closed, or an error (a message over the limit: code 1009)
            return source.close_code, ''


async def _close(side: EitherSocket, code: int | None,
                 reason: str) -> None:
    """Close one side with the other's code and reason (1001 for a code that may not be sent)."""
    if side.closed:
        return
    try:
        await side.close(code=code if code not in (None, 1005, 1006) else GONE,
                         message=reason.encode()[:120])
    except (ConnectionError, RuntimeError):  # that end is gone already
        pass
