"""One function per executable of demo_nodes_cpp (lib/demo_nodes_cpp/<name> calls <name>()).

Upstream's are C++ (rclcpp); these are demo_nodes_py's nodes. Only the talker differs: the C++
one counts from 1 and logs with single quotes.
"""

from demo_nodes_py.services import add_two_ints_client as client
from demo_nodes_py.services import add_two_ints_client_async as client_async
from demo_nodes_py.services import add_two_ints_server as server
from demo_nodes_py.services import introspection
from demo_nodes_py.topics import listener as listener_node
from demo_nodes_py.topics.talker import Talker
from owl_common.run import spin_node


def talker(args: list[str] | None = None) -> None:
    """Publish 'Hello World: N' on chatter, from 1, once a second."""
    spin_node(lambda: Talker(first_count=1, log_line="Publishing: '{}'"), args)


listener = listener_node.main
add_two_ints_server = server.main
add_two_ints_client = client.main
add_two_ints_client_async = client_async.main
introspection_service = introspection.service_main
introspection_client = introspection.client_main
