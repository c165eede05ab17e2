"""A reverse proxy that serves this machine's ports under /user/<name>/proxy/<port>/, for the tests.

It forwards as jupyter-server-proxy does on a class server (its handlers.py, read for the facts): the
prefix is stripped, the browser's Host and Origin go through unchanged, X-Forwarded-Prefix is added
to HTTP requests (not to WebSockets), and WebSockets are relayed message for message. So a page that
works behind it works behind a class server's proxy. Nothing of the product is used here: a page that
only works because both sides share a mistake would not pass.
"""

from __future__ import annotations

import asyncio
import re
import socket
import threading

import aiohttp
from aiohttp import web

HOP = {'connection', 'keep-alive', 'te', 'trailer', 'transfer-encoding', 'upgrade', 'content-length',
       'sec-websocket-key', 'sec-websocket-version', 'sec-websocket-extensions', 'sec-websocket-accept'}
PATH = re.compile(r'^(/user/[a-z0-9]+/proxy/(\d+))(/.*)?$')


class PrefixProxy:
    """The proxy on a port of 127.0.0.1 of its own, in a thread; url names it, close() stops it."""

    def __init__(self) -> None:
        self._socket = socket.socket()
        self._socket.bind(('127.0.0.1', 0))
        self._socket.listen(64)
        self.port = self._socket.getsockname()[1]
        self._loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._thread = threading.Thread(target=self._serve, name='prefix proxy', daemon=True)
        self._thread.start()
        self._ready.wait(10)

    def url(self, name: str, port: int, host: str = '127.0.0.1') -> str:
        """Where the proxy serves a port of a user's: http://<host>:<proxy port>/user/<name>/proxy/<port>/."""
        return f'http://{host}:{self.port}/user/{name}/proxy/{port}/'

    def _serve(self) -> None:
        asyncio.set_event_loop(self._loop)
        app = web.Application(client_max_size=0)
        app.router.add_route('*', '/{path:.*}', self._forward)
        self._runner = web.AppRunner(app, access_log=None, handle_signals=False)
        self._loop.run_until_complete(self._runner.setup())
        self._loop.run_until_complete(web.SockSite(self._runner, self._socket).start())
        self._session = aiohttp.ClientSession(loop=self._loop, auto_decompress=False)
        self._ready.set()
        self._loop.run_forever()

    async def _forward(self, request: web.Request) -> web.StreamResponse:
        match = PATH.match(request.rel_url.raw_path)
        if match is None:
            return web.Response(status=404, text='not a proxied path')
        prefix, port, rest = match.group(1), match.group(2), match.group(3) or '/'
        query = f'?{request.rel_url.raw_query_string}' if request.rel_url.raw_query_string else ''
        target = f'http://127.0.0.1:{port}{rest}{query}'
        headers = {k: v for k, v in request.headers.items() if k.lower() not in HOP}
        if request.headers.get('Upgrade', '').lower() == 'websocket':
            return await self._websocket(request, target.replace('http', 'ws', 1), headers)
        headers['X-Forwarded-Prefix'] = prefix
        body = await request.read() if request.body_exists else None
        async with self._session.request(request.method, target, headers=headers, allow_redirects=False,
                                         data=body) as answer:
            body = await answer.read()
            return web.Response(status=answer.status, body=body, headers={
                k: v for k, v in answer.headers.items() if k.lower() not in HOP})

    async def _websocket(self, request: web.Request, target: str,
                         headers: dict[str, str]) -> web.StreamResponse:
        try:
            upstream = await self._session.ws_connect(target, headers=headers, max_msg_size=0)
        except aiohttp.WSServerHandshakeError as error:
            return web.Response(status=error.status, text='refused upstream')
        browser = web.WebSocketResponse(max_msg_size=0)
        await browser.prepare(request)

        async def relay(source, sink) -> None:
            async for message in source:
                if message.type == aiohttp.WSMsgType.TEXT:
                    await sink.send_str(message.data)
                elif message.type == aiohttp.WSMsgType.BINARY:
                    await sink.send_bytes(message.data)
            await sink.close()
        await asyncio.gather(relay(browser, upstream), relay(upstream, browser), return_exceptions=True)
        return browser

    def close(self) -> None:
        async def stop() -> None:
            await self._session.close()
            await self._runner.cleanup()
        asyncio.run_coroutine_threadsafe(stop(), self._loop).result(10)
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join(10)
        self._socket.close()
