"""The `ros2` daemon: one background process per ROS domain that keeps a warm graph cache.

It serves the graph queries of owl_common.graph.GraphQueries over XML-RPC at
http://127.0.0.1:<11511 + ROS_DOMAIN_ID>/ros2cli/, like upstream's daemon, and the same calls as
JSON at /ros2cli/json, which our own client uses: importing xmlrpc.client (http.client, email,
ssl) took 45 ms of every warm `ros2` call, a third of it.
"""

from owl_common import ros_env

BASE_PORT = 11511
RPC_PATH = '/ros2cli/'
JSON_PATH = '/ros2cli/json'  # a POST of {"method": name, "params": [...]}


def domain_id() -> int:
    """This shell's ROS domain; RuntimeError, one line `ros2` prints, for a ROS_DOMAIN_ID no node can use.

    Not domain 0 instead: that would show another domain's graph as if it were this shell's.
    """
    try:
        return ros_env.domain_id()
    except ros_env.DomainIdError as error:
        raise RuntimeError(f'ros2: {error}') from None


def daemon_port(domain: int | None = None) -> int:
    """The daemon's XML-RPC port for a domain (by default this shell's): BASE_PORT + the domain id."""
    return BASE_PORT + (domain_id() if domain is None else domain)
