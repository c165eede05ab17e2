"""The server of our pages: static files, the pages' npm libraries, a JSON API and one WebSocket.

It listens on a loopback address only and runs aiohttp in a thread of its own beside an rclpy node.
The socket listens from the start; aiohttp is imported and set up when the first connection arrives
(its import is 0.2 s of CPU, a quarter of a simulated module's start-up, and most modules' pages are
never opened), and that connection waits in the socket's queue meanwhile.

    server = WebServer('rqt', STATIC_DIR, port=8093)        # binds now: a busy port is an OSError here
    server.route('GET', '/api/topics', list_topics)          # handler(Request) -> data or (status, data)
    server.channel('graph', open_graph, close_graph)         # pages subscribe over /ws
    server.join_front_door(tool_page('rqt'), page_catalogue())  # also at http://127.0.0.1:8090/rqt/
    server.start()
    ...
    subscription.send({...})                                 # from any thread: pushed to that page
    server.stop()

Paths: `/` is STATIC_DIR/index.html, `/static/<file>` a file of STATIC_DIR, `/owl/<file>` a file
shared by every page (owl_web/static: socket.js, the browser's half of the codec), `/lib/<package>/
<path>` a file of a package that web/package.json depends on (installed by `make setup` into
web/node_modules; nothing comes from a CDN), `/api/...` the routes, `/ws` the WebSocket. A page
refers to all of them relatively (`static/app.js`, `api/topics`, `ws`), so it works the same at
its own address, under the front door (owl_web.front_door) and behind any proxy's path prefix.

Handlers and channel callbacks run in a thread each (they may block on ROS: a service call can
take seconds), never on the event loop. Whatever a client sends, the answer to a bad request is
one line ({"error": ...} or an "error" message) and the server keeps serving.
"""

from __future__ import annotations

import asyncio
import errno
import ipaddress
import json
import logging
import os
import re
import selectors
import socket
import sys
import threading
from collections import deque
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from owl_common.hints import did_you_mean

from owl_web import codec, pages
from owl_web.codec import ApiError
from owl_web.origins import TrustedOrigins, request_refusal
from owl_web.owner_only import OwnerOnly
from owl_web.pages import Page

if TYPE_CHECKING:
    from aiohttp import web

OWL_STATIC = Path(__file__).parent / 'static'
CONTENT_TYPES = {
    '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8',
    '.mjs': 'text/javascript; charset=utf-8', '.css': 'text/css; charset=utf-8',
    '.svg': 'image/svg+xml', '.png': 'image/png', '.json': 'application/json', '.map': 'application/json',
}
LIBRARY_SUFFIXES = ('.js', '.mjs', '.css', '.map')
MAX_PENDING_ERRORS = 100  # per connection: error messages wait in order, beyond that the oldest go
STOP_TIMEOUT = 5.0  # s
MESSAGE_TYPES = ('subscribe', 'unsubscribe', 'command')  # what a page may send


def web_dir() -> Path | None:
    """The repository's web/ folder (package.json, node_modules), found through env.sh's OWL_ROOT."""
    root = os.environ.get('OWL_ROOT')
    return Path(root) / 'web' if root else None


def library_packages(web: Path | None) -> list[str]:
    """The npm packages the pages may load: web/package.json's dependencies."""
    if web is None:
        return []
    try:
        return sorted(json.loads((web / 'package.json').read_text())['dependencies'])
    except (TypeError, OSError, ValueError, KeyError):
        return []


class OneLineLog(logging.Handler):
    """aiohttp's own log records (a malformed HTTP request, say) as one line each, never a traceback."""

    def __init__(self, log: Callable[[str], None]) -> None:
        super().__init__(logging.WARNING)
        self.log = log

    def emit(self, record: logging.LogRecord) -> None:
        """Hand the record to log as one line, with its exception's reason if it has one."""
        line = record.getMessage().strip().splitlines()[0] if record.getMessage().strip() else record.name
        error = record.exc_info[1] if record.exc_info else None
        if error is not None:
            # aiohttp's HTTP errors carry their reason in .message, over several lines
            reason = str(getattr(error, 'message', '') or '').strip() or codec.one_line(error)
            line += f': {reason.splitlines()[0].rstrip(":")}'
        self.log(line)


def one_line_logger(name: str, log: Callable[[str], None]) -> logging.Logger:
    """The logger a server hands aiohttp: its records go to log, one line each."""
    logger = logging.getLogger(f'owl_web.server.{name}')
    logger.propagate = False
    for handler in list(logger.handlers):
        logger.removeHandler(handler)
    logger.addHandler(OneLineLog(log))
    return logger


@dataclass
class Request:
    """What a route handler gets: the path's {name} parts, the query (last value of each key), the body.

    headers are the request's as the server got them (through the front door: as it forwarded them).
    """

    method: str
    path: str
    params: dict[str, str]
    query: dict[str, str]
    body: bytes
    headers: Mapping[str, str] = field(default_factory=dict)

    def json(self) -> dict[str, Any]:
        """The body as a JSON object ({} when empty); a 400 ApiError saying what is wrong otherwise."""
        return codec.parse_json_object(self.body)


@dataclass
class Route:
    """A route as route() registered it: method, path, the path's regex and the handler."""

    method: str
    path: str  # as given, e.g. '/api/publishers/{id}'
    pattern: re.Pattern
    handler: Callable[[Request], Any]


@dataclass
class Channel:
    """A channel as channel() registered it: its name and its open and close callbacks."""

    name: str
    open: Callable[[Subscription], None]
    close: Callable[[Subscription], None] | None


class Subscription:
    """One page's subscription to a channel; send*/error may be called from any thread and never block.

    An update not yet sent is replaced by a newer one (a page wants the newest state, and a slow page
    must not hold up ROS callbacks); errors wait in order.
    """

    def __init__(self, connection: Connection, subscription_id: int | str, channel: str,
                 params: dict[str, Any]) -> None:
        self.connection = connection
        self.id = subscription_id
        self.channel = channel
        self.params = params  # the subscribe message without type, id and channel
        self.active = True

    def send(self, data: dict[str, Any]) -> None:
        """Push data to the page as an "update", in place of one of this subscription not yet sent."""
        self.connection.offer(self, codec.encode(codec.update(self.id, data)))

    def send_binary(self, data: dict[str, Any], payload: bytes) -> None:
        """Push data with a binary payload (an image, say) as a frame, in place of one not yet sent."""
        self.connection.offer(self, codec.pack_frame(codec.update(self.id, data), payload))

    def error(self, message: str) -> None:
        """Send the page an error line for this subscription, in order with other errors (none once ended)."""
        if self.active:
            self.connection.error(self.id, message)

    def pending(self) -> bool:
        """Whether an update of this subscription still waits to be sent (the next one takes its place).

        A channel whose updates each carry only what is new (the robot view's plots) makes the next
        one cover what the waiting one did.
        """
        return self.connection.has_pending(self)


class Connection:
    """One page's WebSocket: its subscriptions and what waits to be sent to it."""

    def __init__(self, websocket: web.WebSocketResponse, loop: asyncio.AbstractEventLoop) -> None:
        self.websocket = websocket
        self.loop = loop
        self.subscriptions: dict[int | str, Subscription] = {}
        self._lock = threading.Lock()
        self._updates: dict[int | str, str | bytes] = {}
        self._errors: deque[str] = deque(maxlen=MAX_PENDING_ERRORS)
        self._wake = asyncio.Event()
        self._wake_pending = False  # a wake-up is on its way to the sender (see _wake_sender)
        self.closed = False

    def offer(self, subscription: Subscription, message: str | bytes) -> None:
        """Queue a subscription's message in place of one not yet sent; nothing once either has ended."""
        with self._lock:
            if not subscription.active or self.closed:
                return
            self._updates[subscription.id] = message
            wake = self._wake_sender()
        if wake:
            self._notify()

    def has_pending(self, subscription: Subscription) -> bool:
        """Whether an update of the subscription is queued and not sent yet."""
        with self._lock:
            return subscription.id in self._updates

    def error(self, subscription_id: int | str | None, message: str) -> None:
        """Queue an error line after the others (beyond MAX_PENDING_ERRORS the oldest go)."""
        with self._lock:
            if self.closed:
                return
            self._errors.append(codec.encode(codec.error(subscription_id, message)))
            wake = self._wake_sender()
        if wake:
            self._notify()

    def done(self, command_id: int | str | None, result: dict[str, Any] | None = None) -> None:
        """A command carried out: kept in order with the error lines (it answers a request)."""
        with self._lock:
            if self.closed:
                return
            self._errors.append(codec.encode(codec.done(command_id, result)))
            wake = self._wake_sender()
        if wake:
            self._notify()

    def forget(self, subscription: Subscription) -> None:
        """End a subscription: its pending update is dropped and nothing more is sent for it."""
        with self._lock:
            subscription.active = False
            self._updates.pop(subscription.id, None)
            self.subscriptions.pop(subscription.id, None)

    def close(self) -> None:
        """Mark the connection closed: nothing more is queued for the page."""
        with self._lock:
            self.closed = True

    def _wake_sender(self) -> bool:
        """Whether the sender must be woken for what was just queued (called with the lock held).

        One wake-up per batch: the sender takes everything queued until it runs, and a wake-up costs
        the event loop's self-pipe a write, which at 100 kit states a second was 8 % of robot_view.
        """
        wake = not self._wake_pending
        self._wake_pending = True
        return wake

    def _notify(self) -> None:
        try:
            self.loop.call_soon_threadsafe(self._wake.set)
        except RuntimeError:  # the loop has stopped: the server is going away
            pass

    async def send_pending(self) -> None:
        """The connection's sender: wait for messages and send them, errors first.

        It runs until the page goes away (then the receiving side ends the connection).
        """
        try:
            while True:
                await self._wake.wait()
                self._wake.clear()
                with self._lock:
                    messages = [*self._errors, *self._updates.values()]
                    self._errors.clear()
                    self._updates.clear()
                    self._wake_pending = False
                for message in messages:
                    if isinstance(message, bytes):
                        await self.websocket.send_bytes(message)
                    else:
                        await self.websocket.send_str(message)
        except (ConnectionError, RuntimeError):  # the page closed the connection mid-send
            return


# On a machine the accounts of a class share, each student's robot view, rqt and module pages ask for
# the same ports: with this set to 1 (the class server does), a page whose port is taken serves on a
# free one instead of failing; each student reaches their own pages through their front door.
PORT_FALLBACK_VARIABLE = 'OWL_PAGE_PORT_FALLBACK'


class WebServer:
    """Static files, libraries, JSON routes and the WebSocket of one page (or a few) on host:port."""

    def __init__(self, name: str, static_dir: Path, port: int = 0, host: str = '127.0.0.1',
                 log: Callable[[str], None] | None = None) -> None:
        """Binds at once (OSError for a busy port, unless OWL_PAGE_PORT_FALLBACK=1 gives a free one).

        name prefixes the lines the server prints; log (default: stderr) gets one line for each
        internal error. ValueError for a host that is not a loopback address, or a malformed
        OWL_TRUSTED_ORIGINS.
        """
        address = ipaddress.ip_address(host)
        if address.version != 4 or not address.is_loopback:
            raise ValueError(f'{name} serves on loopback addresses only (127.x.y.z), not {host}')
        self.trusted = TrustedOrigins.from_environment()
        self.owner_only = OwnerOnly.from_environment()
        self.name = name
        self.static_dir = static_dir
        self.log = log or (lambda line: print(f'{name}: {line}', file=sys.stderr, flush=True))
        self.web = web_dir()
        self.libraries = library_packages(self.web)
        self._routes: list[Route] = []
        self._channels: dict[str, Channel] = {}
        self._commands: dict[str, Callable[[dict[str, Any]], dict[str, Any] | None]] = {}
        self._commands_at_once: set[str] = set()  # see command()
        self._connections: set[Connection] = set()
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        try:
            self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            try:
                self._socket.bind((host, port))
            except OSError as error:
                fallback = os.environ.get(PORT_FALLBACK_VARIABLE) == '1'
                if error.errno != errno.EADDRINUSE or port == 0 or not fallback:
                    raise
                self._socket.bind((host, 0))
            self._socket.listen(64)
        except OSError:
            self._socket.close()
            raise
        self._loop: asyncio.AbstractEventLoop | None = None
        self._runner: web.AppRunner | None = None
        self._thread: threading.Thread | None = None
        self._stopping = threading.Lock()
        self._stopped = False
        # stop() wakes a server still waiting for its first connection through this pipe
        self._wake_reader, self._wake_writer = os.pipe()
        self._page: Page | None = None  # as join_front_door() gave it
        self._catalogue: list[Page] = []
        self._registered: Page | None = None  # the entry in the pages folder while serving
        self.front_door: str | None = None  # the front door's URL once joined and started

    @property
    def url(self) -> str:
        """The address the server answers at, e.g. http://127.0.0.1:8090/ (the bound port, if 0 was asked)."""
        host, port = self._socket.getsockname()[:2]
        return f'http://{host}:{port}/'

    @property
    def address(self) -> str:
        """Where a student opens the page: under the front door when it runs, else the server's own url."""
        if self.front_door and self._page is not None:
            return f'{self.front_door}{self._page.mount}/'
        return self.url

    def missing_libraries(self) -> str | None:
        """A line saying the pages' libraries are not installed, or None when they are."""
        if self.web is None:
            return "OWL_ROOT is not set ('source env.sh'): the pages' libraries cannot be found"
        installed = self.web / 'node_modules'
        missing = [p for p in self.libraries if not (installed / p / 'package.json').is_file()]
        if not self.libraries or missing:
            return (f"the pages' libraries ({', '.join(missing) or 'web/package.json'}) are not installed: "
                    "run 'make setup'")
        return None

    # ---- what the application adds before start() --------------------------------------------

    def join_front_door(self, page: Mapping[str, str], catalogue: Iterable[Mapping[str, str]]) -> None:
        """List this page at the front door once it serves, under page's mount, and start the front door.

        page and each of catalogue are owl_web.pages.Page's fields (mount, title, start, address);
        catalogue is every page the kit knows, so the front door can say how to start one that does
        not run. Also serves GET /api/kit-pages: the other pages that run now (owl/links.js shows
        them as links on the page). ValueError for a page that is not one.
        """
        self._page = Page.from_json(dict(page))
        self._catalogue = [Page.from_json(dict(entry)) for entry in catalogue]
        self.route('GET', '/api/kit-pages', self._kit_pages)

    def _kit_pages(self, _: Request) -> dict[str, Any]:
        own = self._page.mount if self._page is not None else None
        running = [state.page for state in pages.page_states(pages.pages_dir())
                   if state.running and state.page.mount != own]
        return {'front_door': self.front_door or '',
                'pages': [{'name': page.title, 'mount': page.mount, 'url': page.url} for page in running]}

    def _join(self) -> None:
        """Register the page in the pages folder and make sure a front door runs (start() calls it).

        A page that cannot join says why in one line and serves at its own address anyway.
        """
        if self._page is None:
            return
        folder = pages.pages_dir()
        entry = replace(self._page, url=self.url, pid=os.getpid())
        try:
            pages.register(entry, folder)
            self._registered = entry
            pages.write_catalogue(self._catalogue, folder)
            if pages.front_door_wanted():
                self.front_door = pages.ensure_front_door(folder)
        except (pages.PagesError, ValueError, OSError) as error:
            self.log(f'not at the front door: {codec.one_line(error)} (the page is at {self.url})')

    def route(self, method: str, path: str, handler: Callable[[Request], Any]) -> None:
        """handler(Request) returns JSON data, or (status, data); it raises ApiError to refuse."""
        pattern = re.compile('^' + re.sub(r'\\\{(\w+)\\\}', r'(?P<\1>[^/]+)', re.escape(path)) + '$')
        self._routes.append(Route(method, path, pattern, handler))

    def channel(self, name: str, open: Callable[[Subscription], None],
                close: Callable[[Subscription], None] | None = None) -> None:
        """Add a channel: open(subscription) starts pushing to it (ApiError refuses the subscription).

        close is called once when the page unsubscribes or goes away.
        """
        self._channels[name] = Channel(name, open, close)

    def command(self, name: str, handler: Callable[[dict[str, Any]], dict[str, Any] | None],
                at_once: bool = False) -> None:
        """Add a command: handler(arguments) carries out a page's {"type": "command", "name": name, ...}.

        The arguments are the message without type, id and name; the handler raises ApiError to refuse,
        before anything reaches ROS. Runs in a worker thread; the page gets {"type": "done"} (with
        "result": what the handler returned, when it returns a dict: what came of the command) or
        the error line. A handler that never waits (one that only publishes) may run at_once, in the
        server's own thread: a drag's commands then reach ROS without two hand-overs between threads,
        each of which waits for Python's lock on a busy machine.
        """
        self._commands[name] = handler
        if at_once:
            self._commands_at_once.add(name)

    # ---- running ---------------------------------------------------------------------------

    def start(self) -> None:
        """Serve in a background thread, from the first connection on (the socket already queues it)."""
        self._thread = threading.Thread(target=self._serve, name=f'{self.name} web', daemon=True)
        self._thread.start()
        self._join()

    def _serve(self) -> None:
        """Wait for the first connection (or stop()), then set aiohttp up and serve until stop()."""
        with selectors.DefaultSelector() as waiting:
            waiting.register(self._socket, selectors.EVENT_READ)
            waiting.register(self._wake_reader, selectors.EVENT_READ)
            while not any(key.fileobj is self._socket for key, _ in waiting.select()):
                if self._stopped:
                    return
        loop = asyncio.new_event_loop()
        with self._stopping:
            if self._stopped:
                loop.close()
                return
            self._loop = loop
        try:
            loop.run_until_complete(self._start_site())
        except Exception as error:  # no page then: say why, once
            if not self._stopped:
                self.log(f'cannot serve: {codec.one_line(error)}')
            loop.close()
            return
        loop.run_forever()
        loop.close()

    def stop(self) -> None:
        """Close every page's WebSocket (going away) and stop serving; a second call does nothing."""
        with self._stopping:
            if self._stopped:
                return
            loop, thread = self._loop, self._thread
            self._loop = self._thread = None
            self._stopped = True
            registered, self._registered = self._registered, None
        if registered is not None:
            pages.unregister(registered, pages.pages_dir())
        os.write(self._wake_writer, b'.')  # a server still waiting for its first connection
        if loop is not None and thread is not None:
            try:
                asyncio.run_coroutine_threadsafe(self._shutdown(), loop).result(STOP_TIMEOUT)
            except Exception as error:  # a stop must finish; say why it was not clean
                self.log(f'stopping the web server: {codec.one_line(error)}')
            try:
                loop.call_soon_threadsafe(loop.stop)
            except RuntimeError:  # already stopped
                pass
        if thread is not None:
            thread.join(STOP_TIMEOUT)
        self._socket.close()
        os.close(self._wake_reader)
        os.close(self._wake_writer)

    async def _start_site(self) -> None:
        from aiohttp import web

        @web.middleware
        async def own_pages_only(request: web.Request, handler: Callable[..., Any]) -> web.StreamResponse:
            refusal = request_refusal(request.headers, request.transport, self.trusted, self.owner_only)
            if refusal is not None:
                return json_response(403, {'error': refusal})
            return await handler(request)

        logger = one_line_logger(self.name, self.log)
        asyncio.get_running_loop().set_exception_handler(
            lambda loop, context: self.log(f"{context.get('message', 'event loop error')}"
                                           + (f": {codec.one_line(context['exception'])}"
                                              if context.get('exception') else '')))
        app = web.Application(client_max_size=codec.MAX_BODY, logger=logger,
                              middlewares=[own_pages_only])
        app.router.add_get('/ws', self._websocket)
        app.router.add_route('*', '/{path:.*}', self._http)
        self._runner = web.AppRunner(app, handle_signals=False, access_log=None, shutdown_timeout=0.5,
                                     logger=logger)
        await self._runner.setup()
        await web.SockSite(self._runner, self._socket).start()

    async def _shutdown(self) -> None:
        from aiohttp import WSCloseCode

        for connection in list(self._connections):
            await connection.websocket.close(code=WSCloseCode.GOING_AWAY, message=b'server stopped')
        if self._runner is not None:
            await self._runner.cleanup()

    async def _in_thread(self, function: Callable[..., Any], *args: Any) -> Any:
        """function(*args) in a daemon thread of its own.

        A handler blocked on ROS then holds neither the event loop nor the process's exit (a thread
        pool's workers would hold both).
        """
        loop = asyncio.get_running_loop()
        future = loop.create_future()

        def settle(result: Any, error: BaseException | None) -> None:
            if not future.done():
                future.set_exception(error) if error is not None else future.set_result(result)

        def run() -> None:
            try:
                result, error = function(*args), None
            except BaseException as raised:  # handed to the awaiting coroutine
                result, error = None, raised
            try:
                loop.call_soon_threadsafe(settle, result, error)
            except RuntimeError:  # the loop has stopped meanwhile
                pass

        threading.Thread(target=run, name=f'{self.name} handler', daemon=True).start()
        return await future

    # ---- HTTP ------------------------------------------------------------------------------

    async def _http(self, request: web.Request) -> web.StreamResponse:
        try:
            if request.method == 'GET' and not request.path.startswith('/api/'):
                return self._file(request.path)
            route, params = self._find_route(request.method, request.path)
            body = await self._read_body(request)
            api_request = Request(request.method, request.path, params,
                                  {key: request.query.getall(key)[-1] for key in request.query}, body,
                                  dict(request.headers))
            result = await self._in_thread(route.handler, api_request)
            status, data = result if isinstance(result, tuple) else (200, result)
            return json_response(status, data)
        except ApiError as error:
            return json_response(error.status, {'error': error.message})
        except Exception as error:  # a bug must not take the page down: one line, the server lives on
            line = codec.one_line(error)
            self.log(f'{request.method} {request.path}: {line}')
            return json_response(500, {'error': f'internal error: {line}'})

    def _find_route(self, method: str, path: str) -> tuple[Route, dict[str, str]]:
        matching = [(route, match) for route in self._routes if (match := route.pattern.match(path))]
        for route, match in matching:
            if route.method == method:
                return route, match.groupdict()
        if matching:
            raise ApiError(405, f'{method} is not allowed on {path}')
        known = sorted({route.path for route in self._routes})
        raise ApiError(404, f"no API path '{path}'; known: {', '.join(known)}")

    @staticmethod
    async def _read_body(request: web.Request) -> bytes:
        from aiohttp import web

        if request.content_length is not None and request.content_length > codec.MAX_BODY:
            raise ApiError(413, f'request body of {request.content_length} bytes is over the limit '
                                f'of {codec.MAX_BODY}')
        try:
            return await request.read()
        except web.HTTPRequestEntityTooLarge:
            raise ApiError(413, f'request body is over the limit of {codec.MAX_BODY} bytes') from None

    def _file(self, path: str) -> web.Response:
        """A page's file, a shared file or a library file; 404 for anything else."""
        file = None
        if path in ('/', '/index.html'):
            file = self.static_dir / 'index.html'
        elif path.startswith('/static/'):
            file = _flat_file(self.static_dir, path.removeprefix('/static/'))
        elif path.startswith('/owl/'):
            file = _flat_file(OWL_STATIC, path.removeprefix('/owl/'))
        elif path.startswith('/lib/') and self.web is not None:
            file = self._library_file(path.removeprefix('/lib/'))
        if file is None or file.suffix not in CONTENT_TYPES or not file.is_file():
            raise ApiError(404, f"no page '{path}'")
        from aiohttp import web

        return web.Response(body=file.read_bytes(), headers={
            'Content-Type': CONTENT_TYPES[file.suffix], 'Cache-Control': 'no-cache'})

    def _library_file(self, rest: str) -> Path | None:
        """web/node_modules/<package>/<path> for a package of web/package.json, never outside it."""
        package = next((p for p in self.libraries if rest.startswith(p + '/')), None)
        if package is None or self.web is None or not rest.endswith(LIBRARY_SUFFIXES):
            return None
        base = (self.web / 'node_modules' / package).resolve()
        file = (base / rest.removeprefix(package + '/')).resolve()
        return file if file.is_relative_to(base) else None

    # ---- WebSocket -------------------------------------------------------------------------

    async def _websocket(self, request: web.Request) -> web.WebSocketResponse:
        # A message up to MAX_BODY gets a one-line error when over MAX_CLIENT_MESSAGE; a bigger one
        # closes the connection with the protocol's own "message too big" (1009).
        # No permessage-deflate: on 127.0.0.1 it only costs CPU at both ends, and most of the bytes
        # are camera frames (JPEG or PNG, compressed already), which aiohttp deflated in a worker
        # thread, one more hand-over of the GIL between a frame and the page.
        from aiohttp import WSMsgType, web

        websocket = web.WebSocketResponse(max_msg_size=codec.MAX_BODY, compress=False)
        await websocket.prepare(request)
        connection = Connection(websocket, asyncio.get_running_loop())
        self._connections.add(connection)
        sender = asyncio.create_task(connection.send_pending())
        try:
            async for message in websocket:
                if message.type == WSMsgType.TEXT:
                    await self._client_message(connection, message.data)
                elif message.type == WSMsgType.BINARY:
                    connection.error(None, 'binary messages are not accepted: send JSON text')
                elif message.type == WSMsgType.ERROR:
                    self.log(f'closed a WebSocket connection: {codec.one_line(message.data)}')
        finally:
            sender.cancel()
            connection.close()
            self._connections.discard(connection)
            for subscription in list(connection.subscriptions.values()):
                await self._unsubscribe(connection, subscription)
        return websocket

    async def _client_message(self, connection: Connection, text: str) -> None:
        message_id = None
        try:
            message = codec.decode_client_message(text)
            message_id = message.get('id')
            if message['type'] == 'subscribe':
                await self._subscribe(connection, message)
            elif message['type'] == 'command':
                await self._command(connection, message)
            elif message['type'] == 'unsubscribe':
                codec.check_keys(message, ('type', 'id'), required=('id',))
                subscription = connection.subscriptions.get(message['id'])
                if subscription is None:
                    raise ApiError(404, f"no subscription {json.dumps(message['id'])}")
                await self._unsubscribe(connection, subscription)
            else:
                raise ApiError(400, f"unknown message type {json.dumps(message['type'])}"
                                    f"{did_you_mean(message['type'], MESSAGE_TYPES)}; "
                                    f"expected: {', '.join(MESSAGE_TYPES)}")
        except ApiError as error:
            connection.error(message_id, error.message)
        except Exception as error:  # a bug: one line to the page and the log, the connection lives on
            line = codec.one_line(error)
            self.log(f'WebSocket message: {line}')
            connection.error(message_id, f'internal error: {line}')

    async def _subscribe(self, connection: Connection, message: dict[str, Any]) -> None:
        for key in ('id', 'channel'):
            if key not in message:
                raise ApiError(400, f"missing key '{key}' in the subscribe message")
        name = message['channel']
        channel = self._channels.get(name) if isinstance(name, str) else None
        if channel is None:
            hint = did_you_mean(str(name), self._channels)
            raise ApiError(404, f'unknown channel {json.dumps(name)}{hint}; '
                                f"known: {', '.join(sorted(self._channels))}")
        if message['id'] in connection.subscriptions:
            raise ApiError(400, f"subscription id {json.dumps(message['id'])} is already in use")
        params = {k: v for k, v in message.items() if k not in ('type', 'id', 'channel')}
        subscription = Subscription(connection, message['id'], name, params)
        connection.subscriptions[subscription.id] = subscription
        try:
            await self._in_thread(channel.open, subscription)
        except BaseException:
            connection.forget(subscription)
            raise

    async def _command(self, connection: Connection, message: dict[str, Any]) -> None:
        name = message.get('name')
        handler = self._commands.get(name) if isinstance(name, str) else None
        if handler is None:
            if 'name' not in message:
                raise ApiError(400, "missing key 'name' in the command message")
            hint = did_you_mean(str(name), self._commands)
            raise ApiError(404, f'unknown command {json.dumps(name)[:80]}{hint}; '
                                f"known: {', '.join(sorted(self._commands)) or 'none'}")
        arguments = {k: v for k, v in message.items() if k not in ('type', 'id', 'name')}
        if name in self._commands_at_once:
            result = handler(arguments)
        else:
            result = await self._in_thread(handler, arguments)
        connection.done(message.get('id'), result if isinstance(result, dict) else None)

    async def _unsubscribe(self, connection: Connection, subscription: Subscription) -> None:
        connection.forget(subscription)
        close = self._channels[subscription.channel].close
        if close is not None:
            try:
                await self._in_thread(close, subscription)
            except Exception as error:  # the subscription is gone anyway; say why its clean-up failed
                self.log(f'closing a {subscription.channel} subscription: {codec.one_line(error)}')


def _flat_file(folder: Path, name: str) -> Path | None:
    """folder/name for a plain file name (no sub-folders, no way out of the folder)."""
    return folder / name if name and '/' not in name and not name.startswith('.') else None


def json_response(status: int, data: Any) -> web.Response:
    """An HTTP answer of JSON data with the status, never cached."""
    from aiohttp import web

    return web.Response(status=status, text=json.dumps(data), content_type='application/json',
                        headers={'Cache-Control': 'no-store'})
