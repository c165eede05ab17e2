"""Forwarding a browser's request, or its WebSocket, to a page's own server (the front door's half).

The page's server sees a request from this machine to its own address: Host is its own, an Origin
becomes its own origin (the front door has checked the browser's before), cookies and
authorization stay behind (our pages use neither; a class server's login cookie is not theirs to
see), and nothing of the hop itself (Connection, Upgrade, ...) passes. Bodies stream both ways;
WebSocket messages pass one for one, with the close code of the side that closed.
"""

from __future__ import annotations

import asyncio
from urllib.parse import urlsplit

import aiohttp
from aiohttp import WSMsgType, web

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


def forwarded_headers(request: web.BaseRequest, base_url: str) -> dict[str, str]:
    """The request's headers as the page's server gets them (see the module's docstring)."""
    headers = {name: value for name, value in request.headers.items() if name.lower() not in NOT_FORWARDED}
    if 'Origin' in request.headers:
        headers['Origin'] = own_origin(base_url)
    return headers


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
                request.method, target, headers=forwarded_headers(request, base_url),
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
        page = web.WebSocketResponse(max_msg_size=codec.MAX_BODY, autoping=True)
        await page.prepare(request)
        target = base_url.rstrip('/').replace('http', 'ws', 1) + rest
        try:
            server = await self.session.ws_connect(target, headers=forwarded_headers(request, base_url),
                                                   max_msg_size=FROM_SERVER_LIMIT, autoping=True)
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
