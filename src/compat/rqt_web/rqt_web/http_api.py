"""The local HTTP server: the page's static files and the JSON API over the rqt node.

Every answer to a bad request is a status code and {"error": "<one line>"}; nothing a client
sends ends the server or prints a traceback.
"""

import json
import re
import sys
from collections.abc import Callable
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlsplit

from rqt_web import api_input
from rqt_web.api_input import ApiError

STATIC_DIR = Path(__file__).parent / 'static'
STATIC_TYPES = {'.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8',
                '.css': 'text/css; charset=utf-8', '.svg': 'image/svg+xml'}
MAX_BODY = 1 << 20  # bytes
PUBLISHER_PATH = re.compile(r'^/api/publishers/([^/]+)$')
TRUE_WORDS = ('1', 'true', 'yes', 'on')


class ApiServer(ThreadingHTTPServer):
    """Serves on 127.0.0.1 only; the rqt node sets .backend before serving."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, port: int) -> None:
        super().__init__(('127.0.0.1', port), ApiHandler)
        self.backend: Any = None

    @property
    def url(self) -> str:
        return f'http://127.0.0.1:{self.server_address[1]}/'

    def handle_error(self, request: Any, client_address: Any) -> None:
        # A browser closing a connection mid-answer is normal; anything else gets one line.
        error = sys.exc_info()[1]
        if not isinstance(error, (ConnectionError, TimeoutError)):
            print(f'rqt: error while answering {client_address[0]}: {error!r}', file=sys.stderr)


def _query_flag(query: dict[str, list[str]], key: str, default: bool) -> bool:
    values = query.get(key)
    return default if not values else values[-1].lower() in TRUE_WORDS


def _query_text(query: dict[str, list[str]], key: str) -> str:
    values = query.get(key)
    if not values or not values[-1]:
        raise ApiError(400, f"missing query parameter '{key}'")
    return values[-1]


class ApiHandler(BaseHTTPRequestHandler):
    server: ApiServer
    protocol_version = 'HTTP/1.1'
    server_version = 'rqt_web'

    def log_message(self, format: str, *args: Any) -> None:
        pass  # no access log: the terminal stays readable

    # ---- dispatch ----------------------------------------------------------------------------

    def do_GET(self) -> None:
        self._dispatch('GET')

    def do_POST(self) -> None:
        self._dispatch('POST')

    def do_PATCH(self) -> None:
        self._dispatch('PATCH')

    def do_DELETE(self) -> None:
        self._dispatch('DELETE')

    def _routes(self) -> dict[tuple[str, str], Callable[[dict[str, list[str]]], Any]]:
        backend = self.server.backend
        return {
            ('GET', '/api/graph'): lambda q: backend.graph(_query_flag(q, 'hide_debug', True),
                                                           _query_flag(q, 'hide_leaf_topics', False)),
            ('GET', '/api/topics'): lambda q: _names_and_types(backend.topic_types()),
            ('GET', '/api/image_topics'): lambda q: _names_and_types(backend.image_topic_types()),
            ('GET', '/api/services'): lambda q: _names_and_types(backend.service_types()),
            ('GET', '/api/interface'): lambda q: backend.interface(_query_text(q, 'type')),
            ('GET', '/api/interfaces'): lambda q: backend.interface_names(_query_text(q, 'kind')),
            ('GET', '/api/publishers'): lambda q: backend.message_publishers(),
            ('POST', '/api/publishers'): lambda q: (201, backend.add_message_publisher(self._json_body())),
            ('POST', '/api/call'): lambda q: backend.call_service(self._json_body()),
        }

    def _dispatch(self, method: str) -> None:
        try:
            body = self._read_body()
            url = urlsplit(self.path)
            query = parse_qs(url.query)
            self._body = body
            if method == 'GET' and not url.path.startswith('/api/'):
                self._send_static(url.path)
            elif url.path == '/api/image' and method == 'GET':
                self._send_image(query)
            elif (match := PUBLISHER_PATH.match(url.path)) and method in ('PATCH', 'DELETE'):
                publisher_id = api_input.identifier(match.group(1))
                backend = self.server.backend
                if method == 'PATCH':
                    self._send_json(200, backend.update_message_publisher(publisher_id, self._json_body()))
                else:
                    backend.remove_message_publisher(publisher_id)
                    self._send_json(200, {'deleted': publisher_id})
            else:
                self._send_api(method, url.path, query)
        except ApiError as error:
            self._send_json(error.status, {'error': error.message})
        except (ConnectionError, TimeoutError):
            self.close_connection = True
        except Exception as error:  # a bug must not take the page down: one line, the server lives on
            line = str(error).splitlines()[0] if str(error) else type(error).__name__
            self.server.backend.get_logger().error(f'{method} {self.path}: {line}')
            self._send_json(500, {'error': f'internal error: {line}'})

    def _send_api(self, method: str, path: str, query: dict[str, list[str]]) -> None:
        routes = self._routes()
        handler = routes.get((method, path))
        if handler is None:
            allowed = [m for m, p in routes if p == path]
            if allowed or PUBLISHER_PATH.match(path) or path == '/api/image':
                raise ApiError(405, f'{method} is not allowed on {path}')
            known = sorted({p for _, p in routes} | {'/api/image', '/api/publishers/<id>'})
            raise ApiError(404, f"no API path '{path}'; known: {', '.join(known)}")
        result = handler(query)
        status, data = result if isinstance(result, tuple) else (200, result)
        self._send_json(status, data)

    # ---- input -------------------------------------------------------------------------------

    def _read_body(self) -> bytes:
        length_text = self.headers.get('Content-Length') or '0'
        if not length_text.isdigit():
            self.close_connection = True
            raise ApiError(400, f'bad Content-Length {length_text!r}')
        length = int(length_text)
        if length > MAX_BODY:
            self.close_connection = True
            raise ApiError(413, f'request body of {length} bytes is over the limit of {MAX_BODY}')
        return self.rfile.read(length) if length else b''

    def _json_body(self) -> dict[str, Any]:
        return api_input.parse_json_object(self._body)

    # ---- output ------------------------------------------------------------------------------

    def _send(self, status: int, content_type: str, data: bytes,
              headers: dict[str, str] | None = None) -> None:
        self.send_response(status)
        self.send_header('Content-Type', content_type)
        self.send_header('Content-Length', str(len(data)))
        self.send_header('Cache-Control', 'no-store')
        for key, value in (headers or {}).items():
            self.send_header(key, value)
        self.end_headers()
        self.wfile.write(data)

    def _send_json(self, status: int, data: Any) -> None:
        self._send(status, 'application/json', json.dumps(data).encode())

    def _send_static(self, path: str) -> None:
        name = 'index.html' if path in ('/', '/index.html') else path.removeprefix('/static/')
        file = STATIC_DIR / name
        if '/' in name or file.suffix not in STATIC_TYPES or not file.is_file():
            raise ApiError(404, f"no page '{path}'")
        self._send(200, STATIC_TYPES[file.suffix], file.read_bytes())

    def _send_image(self, query: dict[str, list[str]]) -> None:
        after_text = query.get('after', ['0'])[-1]
        if not after_text.isdigit():
            raise ApiError(400, f"'after' must be a frame number, got {after_text!r}")
        sequence, content_type, data = self.server.backend.latest_image(_query_text(query, 'topic'),
                                                                         int(after_text))
        self._send(200, content_type, data, {'X-Frame': str(sequence)})


def _names_and_types(names: dict[str, list[str]]) -> list[dict[str, Any]]:
    return [{'name': name, 'types': types} for name, types in sorted(names.items())]
