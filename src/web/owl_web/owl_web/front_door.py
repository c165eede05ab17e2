"""The front door: every page of ours through one address on 127.0.0.1, under any path prefix.

    http://127.0.0.1:8090/             the index: every page, running or not, and how to start it
    http://127.0.0.1:8090/rqt/...      rqt's page, its API and its WebSocket, from rqt's own server
    http://127.0.0.1:8090/servo-pan/   a simulated module's page (its own address: 127.42.0.8:8042)
    http://127.0.0.1:8090/api/pages    the index as JSON

WSL2 forwards only 127.0.0.1's ports to the Windows browser, and a class server's proxy serves one
port of each student's under a prefix (/user/NAME/proxy/8090/): one port, relative links, and the
pages' servers found through the pages folder (owl_web.pages) make every page reachable both ways.
The checks of every page (owl_web.origins.request_refusal: Host, Origin, and the account on a class server)
apply here first.

A page server that joins the front door starts it when none runs (owl_web.pages.ensure_front_door).
It runs until stopped (`owl pages --stop`, or its pages folder removed), like ros2's daemon.
"""

from __future__ import annotations

import argparse
import asyncio
import html
import os
import signal
import socket
import sys
from pathlib import Path
from typing import Any

import uvloop
from aiohttp import web

from owl_web import pages
from owl_web.forward import BackendAway, FirstRequest, Forwarder, RequestHead, rewritten_head
from owl_web.origins import TrustedOrigins, request_refusal
from owl_web.owner_only import OwnerOnly
from owl_web.pages import PageState
from owl_web.server import json_response, one_line_logger

FOLDER_CHECK = 2.0  # s between looks whether the pages folder still exists
MOUNT_SHOWN = 80  # characters of an unknown page's name that a 404 repeats
MOUNT_HEADER = 'X-Owl-Mount'  # on every forwarded answer: the page is seen through the front door
REFRESH = 2000  # ms between the index's refreshes


# ---- the index -------------------------------------------------------------------------------------

STYLE = """
body { font: 15px/1.45 system-ui, sans-serif; margin: 0; color: #1d2430; background: #f4f6f8; }
main { max-width: 60rem; margin: 0 auto; padding: 1rem; }
h1 { font-size: 1.4rem; margin: .2rem 0 .8rem; }
.problem { background: #fff3d6; border: 1px solid #e5b94a; padding: .6rem .8rem; border-radius: 6px; }
ul { list-style: none; padding: 0; display: grid; gap: .5rem; }
li { background: #fff; border: 1px solid #d6dbe1; border-radius: 6px; padding: .6rem .8rem; }
li a { font-weight: 600; font-size: 1.05rem; }
li.stopped { color: #7c8591; background: #eceef1; }
li.stopped .title { font-weight: 600; font-size: 1.05rem; }
.state { float: right; font-size: .85rem; }
.running .state { color: #1a7f37; }
code { background: #eef1f4; padding: 0 .25rem; border-radius: 3px; overflow-wrap: anywhere; }
small { display: block; color: #5c6773; }
"""
# The index refreshes itself in place from the same address (a 404's too), so one renderer serves both.
SCRIPT = """
window.frontDoor = { refreshes: 0 };
setInterval(async () => {
  try {
    const answer = await fetch(location.href, { cache: 'no-store' });
    const fresh = new DOMParser().parseFromString(await answer.text(), 'text/html').getElementById('pages');
    if (fresh) document.getElementById('pages').replaceWith(fresh);
    window.frontDoor.refreshes += 1;
  } catch {
    document.getElementById('pages').classList.add('away');
  }
}, REFRESH_MS);
""".replace('REFRESH_MS', str(REFRESH))


def render_index(states: list[PageState], root: str, problem: str = '') -> str:
    """The index's HTML: every page with its state; root leads back to the front door's / (relative)."""
    items = []
    for state in states:
        page = state.page
        module = ''
        if page.address:
            moved = f', now at {html.escape(page.address)}' if page.address != state.course_address else ''
            module = f' · module {html.escape(state.course_address or page.address)} in the course{moved}'
        if state.running:
            items.append(
                f'<li class="page running" data-mount="{page.mount}"><span class="state">running</span>'
                f'<a href="{root}{page.mount}/">{html.escape(page.title)}</a>{module}'
                f'<small>its own address: <code>{html.escape(page.url)}</code></small></li>')
        else:
            start = (f'<small>start it: <code>{html.escape(page.start)}</code></small>' if page.start
                     else '<small>stopped</small>')
            items.append(
                f'<li class="page stopped" data-mount="{page.mount}"><span class="state">not running</span>'
                f'<span class="title">{html.escape(page.title)}</span>{module}{start}</li>')
    running = sum(state.running for state in states)
    problem_html = (f'<p class="problem" id="problem">{html.escape(problem, quote=False)}</p>'
                    if problem else '')
    listing = (f'<ul>{"".join(items)}</ul>' if items else
               '<p>No page has started yet: <code>make demo</code>, <code>rqt</code>, '
               '<code>owl windows</code> or <code>ros2 launch olive_sim owl_kit.launch.py</code> '
               'start some.</p>')
    return (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1"><link rel="icon" href="data:,">'
        f'<title>Owl Kit Lab: pages</title><style>{STYLE}</style></head><body>'
        f'<main id="pages" data-running="{running}"><h1>Owl Kit Lab: every page</h1>{problem_html}{listing}'
        '<p><small>Pages that stop are greyed; this list refreshes by itself. In a terminal: '
        '<code>owl pages</code>.</small></p></main>'
        f'<script>{SCRIPT}</script></body></html>')


def root_of(raw_path: str) -> str:
    """The relative way from a path back to the front door's root: '/' -> './', '/a/b' -> '../'."""
    depth = raw_path.count('/') - 1
    return '../' * depth if depth > 0 else './'


# ---- the server ------------------------------------------------------------------------------------

class FrontDoor:
    """The front door's requests: the index, api/pages, and everything under a page's mount."""

    def __init__(self, folder: Path, trusted: TrustedOrigins, log: Any,
                 owner_only: OwnerOnly | None = None) -> None:
        self.folder = folder
        self.trusted = trusted
        self.owner_only = owner_only or OwnerOnly(on=False)
        self.log = log
        self.forwarder = Forwarder()

    def app(self) -> web.Application:
        """The aiohttp application: the Host and Origin check first, then handle()."""
        app = web.Application(middlewares=[self._own_pages_only], client_max_size=0,
                              logger=one_line_logger('front_door', self.log))
        app.router.add_route('*', '/{path:.*}', self.handle)
        app.on_cleanup.append(lambda _: self.forwarder.close())
        return app

    @web.middleware
    async def _own_pages_only(self, request: web.Request, handler: Any) -> web.StreamResponse:
        refusal = request_refusal(request.headers, request.transport, self.trusted, self.owner_only)
        if refusal is not None:
            return json_response(403, {'error': refusal})
        return await handler(request)

    def websocket_target(self, head: RequestHead, transport: Any) -> tuple[str, bytes] | None:
        """Where a WebSocket request on a connection of its own goes, and the head its page server gets.

        None leaves the request to handle(): a refused one, one for a page that is not running.
        """
        if request_refusal(head.headers, transport, self.trusted, self.owner_only) is not None:
            return None
        path, question, query = head.target.partition('?')
        mount, slash, rest = path[1:].partition('/') if path.startswith('/') else ('', '', '')
        entry = pages.registered(self.folder).get(mount) if slash else None
        if entry is None or not pages.process_alive(entry.pid):
            return None
        return entry.url, rewritten_head(head, entry.url, f'/{rest}{question}{query}')

    async def states(self) -> list[PageState]:
        """page_states of the folder, looked up in a thread (each running page's port is tried)."""
        return await asyncio.to_thread(pages.page_states, self.folder, pages.port_answers, self.log)

    async def handle(self, request: web.Request) -> web.StreamResponse:
        """Answer one request (see the module's docstring for the paths)."""
        raw = request.rel_url.raw_path
        if raw == '/':
            return self.page(200, render_index(await self.states(), './'))
        if raw == '/api/pages':
            if request.method != 'GET':
                return json_response(405, {'error': f'{request.method} is not allowed on /api/pages'})
            return json_response(200, [state.as_json() for state in await self.states()])
        mount, slash, rest = raw[1:].partition('/')
        if not slash:  # /rqt: the page's relative links need /rqt/
            query = f'?{request.rel_url.raw_query_string}' if request.rel_url.raw_query_string else ''
            return web.Response(status=308, headers={'Location': f'{mount}/{query}'})
        entry = pages.registered(self.folder).get(mount)
        if entry is None or not pages.process_alive(entry.pid):
            return await self.not_here(request, mount)
        query = request.rel_url.raw_query_string
        target = f'/{rest}' + (f'?{query}' if query else '')
        if request.headers.get('Upgrade', '').lower() == 'websocket':
            return await self.forwarder.websocket(request, entry.url, target,
                                                  f'{entry.title} stopped; start it: {entry.start}')
        try:
            return await self.forwarder.http(request, entry.url, target, {MOUNT_HEADER: mount})
        except BackendAway:
            return await self.not_here(request, mount)

    async def not_here(self, request: web.Request, mount: str) -> web.StreamResponse:
        """404 (no such page) or 503 (a page that is not running), as the index with the reason on top."""
        states = await self.states()
        known = next((state.page for state in states if state.page.mount == mount), None)
        if known is None:
            status, problem = 404, f"No page '{mount[:MOUNT_SHOWN]}' here. These are the pages:"
        else:
            start = f'; start it: {known.start}' if known.start else ''
            status, problem = 503, f'{known.title} is not running{start}'
        if request.headers.get('Upgrade', '').lower() == 'websocket':
            socket_answer = web.WebSocketResponse()
            await socket_answer.prepare(request)
            await socket_answer.close(code=1013, message=problem.encode()[:120])
            return socket_answer
        if request.rel_url.raw_path.startswith(f'/{mount}/api/') or request.method != 'GET':
            return json_response(status, {'error': problem})
        return self.page(status, render_index(states, root_of(request.rel_url.raw_path), problem))

    @staticmethod
    def page(status: int, text: str) -> web.Response:
        """An HTML answer, never cached."""
        return web.Response(status=status, text=text, content_type='text/html',
                            headers={'Cache-Control': 'no-store'})


async def serve(listener: socket.socket, folder: Path, trusted: TrustedOrigins) -> None:
    """Serve on the listening socket until SIGINT or SIGTERM, or until the pages folder is gone."""
    def log(line: str) -> None:
        print(f'front door: {line}', file=sys.stderr, flush=True)

    door = FrontDoor(folder, trusted, log, OwnerOnly.from_environment())
    runner = web.AppRunner(door.app(), handle_signals=False, access_log=None, shutdown_timeout=0.5)
    await runner.setup()
    http = runner.server
    assert http is not None
    relays: set[asyncio.Transport] = set()  # the WebSockets passed through as bytes
    loop = asyncio.get_running_loop()
    server = await loop.create_server(lambda: FirstRequest(http, door.websocket_target, relays),
                                      sock=listener)
    stop = asyncio.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    while not stop.is_set() and folder.is_dir():
        try:
            await asyncio.wait_for(stop.wait(), FOLDER_CHECK)
        except asyncio.TimeoutError:
            pass
        relays -= {relay for relay in relays if relay.is_closing()}
    server.close()
    for relay in relays:
        relay.close()
    await runner.cleanup()


def main(argv: list[str] | None = None) -> int:
    """The front door's process (ensure_front_door starts it with the listening socket's descriptor)."""
    parser = argparse.ArgumentParser(prog='owl_web.front_door', description=__doc__.split('\n')[0])
    parser.add_argument('--fd', type=int, required=True, help='a listening socket on 127.0.0.1')
    parser.add_argument('--pages-dir', type=Path, required=True, help='the pages folder (owl_web.pages)')
    args = parser.parse_args(argv)
    try:
        trusted = TrustedOrigins.from_environment()
        listener = socket.socket(fileno=args.fd)
    except (ValueError, OSError) as error:
        print(f'front door: {error}', file=sys.stderr)
        return 1
    try:
        uvloop.run(serve(listener, args.pages_dir, trusted))
    finally:
        record = pages.read_json(args.pages_dir / pages.FRONT_DOOR_FILE)
        if isinstance(record, dict) and record.get('pid') == os.getpid():
            (args.pages_dir / pages.FRONT_DOOR_FILE).unlink(missing_ok=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
