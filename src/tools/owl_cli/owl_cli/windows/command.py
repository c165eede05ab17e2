"""The `owl windows` command: the windows' page on 127.0.0.1 until Ctrl-C."""

from __future__ import annotations

import argparse
import os
import sys
import threading
from pathlib import Path

from olive_kit.description import WINDOWS_PORT, page_catalogue, tool_page
from owl_web.origins import port_number

from owl_cli.command import Command


def windows(args: argparse.Namespace) -> int:
    """Run `owl windows`: serve the windows' page until Ctrl-C; exit code 1 when it cannot start."""
    # Imported here: only this command needs the venv's start-up hook (the windows' folder).
    from owl_web.server import WebServer

    from owl_cli.windows.folder import default_windows_dir, private_root
    from owl_cli.windows.page import STATIC_DIR, WindowsPage

    folder = Path(args.folder or os.environ.get('OWL_WINDOWS_DIR') or default_windows_dir())
    try:
        private_root(str(folder))
    except OSError as error:
        print(f'owl windows: cannot use {folder}: {error.strerror or error}', file=sys.stderr)
        return 1
    try:
        server = WebServer('owl windows', STATIC_DIR, args.port)
        server.join_front_door(tool_page('windows'), page_catalogue())
    except OSError as error:
        print(f'owl windows: cannot serve on 127.0.0.1:{args.port}: {error.strerror or error} '
              '(is another owl windows running? choose a port with --port N)', file=sys.stderr)
        return 1
    except ValueError as error:
        print(f'owl windows: {error}', file=sys.stderr)
        return 1
    page = WindowsPage(server, folder)
    stopped = threading.Event()
    try:
        page.start()
        server.start()
        print(f'owl windows: open {server.address} in a browser: the windows of programs without a display '
              f'(from {folder}); Ctrl-C to quit', flush=True)
        stopped.wait()
    except KeyboardInterrupt:
        pass  # Ctrl-C is how a page server is stopped
    finally:
        page.stop()
        server.stop()
    return 0


class WindowsCommand(Command):
    """`owl windows [--port N] [--folder DIR]`."""

    help = 'the windows of programs without a display (cv2.imshow, pygame) on a local page, with their keys'
    description = ('Serve the windows that programs without a display open (cv2.imshow, a pygame '
                   'display; the venv writes their frames to a folder) as one live page on 127.0.0.1, '
                   'and send the keys pressed on it to those programs.')

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """--port, --folder."""
        parser.add_argument('--port', type=port_number, default=WINDOWS_PORT,
                            help=f'HTTP port on 127.0.0.1 (default: {WINDOWS_PORT}; 0 picks a free one)')
        parser.add_argument('--folder', metavar='DIR',
                            help='the windows\' folder (default: $OWL_WINDOWS_DIR, else the one the '
                                 'programs use by default)')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run `owl windows`."""
        return windows(args)
