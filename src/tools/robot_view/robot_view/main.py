"""`robot_view`: the Owl Kit as a live 3D model on http://127.0.0.1:<port>/."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from olive_kit.description import ROBOT_VIEW_PORT, page_catalogue, tool_page
from owl_common.run import spin_node
from owl_web.origins import port_number
from owl_web.server import WebServer
from rclpy.utilities import remove_ros_args

from robot_view.node import RobotViewNode

DEFAULT_PORT = ROBOT_VIEW_PORT
STATIC_DIR = Path(__file__).parent / 'static'


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    """The robot view's own options (--port), from the arguments after the program's name, ROS's removed."""
    parser = argparse.ArgumentParser(
        prog='robot_view', description='The Owl Kit as a live 3D model, its camera, and the '
                                       'simulated IMU turned with the mouse, on one local page.')
    parser.add_argument('--port', type=port_number, default=DEFAULT_PORT,
                        help=f'HTTP port on 127.0.0.1 (default: {DEFAULT_PORT}; 0 picks a free one)')
    return parser.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    """Serve the robot view's page and spin its node until Ctrl-C; exit code 1 when it cannot serve.

    argv is the whole command line, ROS arguments included (None: sys.argv).
    """
    argv = sys.argv if argv is None else argv
    args = parse_arguments(remove_ros_args(argv)[1:])
    try:
        server = WebServer('robot_view', STATIC_DIR, args.port)
        server.join_front_door(tool_page('robot-view'), page_catalogue())
    except OSError as error:
        print(f'robot_view: cannot serve on 127.0.0.1:{args.port}: {error.strerror or error} '
              '(is another robot_view running? choose a port with --port N)', file=sys.stderr)
        sys.exit(1)
    except ValueError as error:
        print(f'robot_view: {error}', file=sys.stderr)
        sys.exit(1)
    missing = server.missing_libraries()
    if missing:
        print(f'robot_view: {missing}', file=sys.stderr)

    def start() -> RobotViewNode:
        node = RobotViewNode(server)
        server.start()  # once the node's channels and commands are there
        print(f'robot_view: open {server.address} in a browser (Ctrl-C to quit)', flush=True)
        return node

    try:
        spin_node(start, argv, events=True)
    finally:
        server.stop()


if __name__ == '__main__':
    main()
