"""`rqt`: start the rqt node and its page (http://127.0.0.1:8090/rqt/ through the front door)."""

import argparse
import os
import sys
import threading
import webbrowser
from pathlib import Path

from olive_kit.description import RQT_PORT, page_catalogue, tool_page
from owl_common.run import spin_node
from owl_humble.launcher import ensure_discovery_bridge
from owl_web.origins import port_number
from owl_web.server import WebServer
from rclpy.utilities import remove_ros_args

from rqt_web.node import RqtWebNode

DEFAULT_PORT = RQT_PORT
STATIC_DIR = Path(__file__).parent / 'static'
# upstream plugin name -> the page's tab (rqt -s rqt_graph opens the Node Graph)
PLUGINS = {'rqt_graph': 'node-graph', 'rqt_publisher': 'message-publisher',
           'rqt_service_caller': 'service-caller', 'rqt_image_view': 'image-view'}


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    """The options of rqt (--port, --no-browser, -s), from the arguments after the program's name."""
    parser = argparse.ArgumentParser(
        prog='rqt', description='rqt in a web browser: Node Graph, Message Publisher, Service Caller '
                                'and Image View on one local page.')
    parser.add_argument('--port', type=port_number, default=DEFAULT_PORT,
                        help=f'HTTP port on 127.0.0.1 (default: {DEFAULT_PORT}; 0 picks a free one)')
    parser.add_argument('--no-browser', action='store_true',
                        help='only print the address, do not open a browser')
    parser.add_argument('-s', '--standalone', choices=sorted(PLUGINS), metavar='PLUGIN',
                        help=f"open the page on one plugin ({', '.join(sorted(PLUGINS))})")
    return parser.parse_args(argv)


def open_browser(url: str) -> None:
    """Try the desktop's browser; headless or failing, the printed address is enough."""
    if not (os.environ.get('DISPLAY') or os.environ.get('WAYLAND_DISPLAY')):
        return
    def open_page() -> None:
        try:
            webbrowser.open(url)
        except Exception:  # any browser trouble: the user still has the printed address
            pass
    # In a thread: some browsers' launchers only return when the browser exits.
    threading.Thread(target=open_page, name='rqt_web browser', daemon=True).start()


def main(argv: list[str] | None = None) -> None:
    """Serve the rqt page and spin its node until Ctrl-C; exit code 1 when it cannot serve.

    argv is the whole command line, ROS arguments included (None: sys.argv).
    """
    argv = sys.argv if argv is None else argv
    args = parse_arguments(remove_ros_args(argv)[1:])
    try:
        server = WebServer('rqt', STATIC_DIR, args.port)
        server.join_front_door(tool_page('rqt'), page_catalogue())
    except OSError as error:
        print(f'rqt: cannot serve on 127.0.0.1:{args.port}: {error.strerror or error} '
              '(is another rqt running? choose a port with --port N)', file=sys.stderr)
        sys.exit(1)
    except ValueError as error:
        print(f'rqt: {error}', file=sys.stderr)
        sys.exit(1)
    missing = server.missing_libraries()
    if missing:
        print(f'rqt: {missing}', file=sys.stderr)
    tab = f'#{PLUGINS[args.standalone]}' if args.standalone else ''

    def start() -> RqtWebNode:
        ensure_discovery_bridge()  # the node graph names Humble modules' nodes too
        node = RqtWebNode(server)  # starts the server: its address under the front door is known then
        url = server.address + tab
        print(f'rqt: open {url} in a browser (Ctrl-C to quit)', flush=True)
        if not args.no_browser:
            open_browser(url)
        return node

    try:
        spin_node(start, argv)
    finally:
        server.stop()


if __name__ == '__main__':
    main()
