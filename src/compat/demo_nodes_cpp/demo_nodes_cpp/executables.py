"""One function per executable of demo_nodes_cpp (lib/demo_nodes_cpp/<name> calls <name>()).

Upstream's are C++ (rclcpp); these are demo_nodes_py's nodes, with what the C++ ones do
differently: the talker counts from 1, logs with single quotes and keeps 7 messages; the clients
log their waiting line where Python's print it; the server has the `one_shot` parameter; the
introspection service and client are two executables.
"""

from functools import partial

import rclpy
from demo_nodes_py.services import add_two_ints_client as client
from demo_nodes_py.services import add_two_ints_client_async as client_async
from demo_nodes_py.services import add_two_ints_server as server
from demo_nodes_py.services import introspection
from demo_nodes_py.topics import listener as listener_node
from demo_nodes_py.topics.talker import Talker
from owl_common.run import spin_node


def talker(args: list[str] | None = None) -> None:
    """Publish 'Hello World: N' on chatter, from 1, once a second."""
    spin_node(lambda: Talker(first_count=1, log_line="Publishing: '{}'", depth=7), args)


listener = listener_node.main


def add_two_ints_server(args: list[str] | None = None) -> None:
    """Serve add_two_ints until Ctrl-C, or until the first answer with `-p one_shot:=true`."""
    spin_node(partial(server.AddTwoIntsServer, with_one_shot=True), args)


def add_two_ints_client(args: list[str] | None = None) -> None:
    """One request, awaited with spin_until_future_complete."""
    client.run_client(args, rclpy.spin_until_future_complete, client.log_line)


def add_two_ints_client_async(args: list[str] | None = None) -> None:
    """One request, awaited with a spin_once loop."""
    client.run_client(args, client_async.spin_until_done, client.log_line)


introspection_service = introspection.service_main
introspection_client = introspection.client_main
