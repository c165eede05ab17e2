"""Graph queries answered from an rclpy node as plain data, and the rules of node and topic names.

The answers are lists, dicts and strings; ros2cli, rqt_web and owl_web share both parts.

The same class serves a verb's own DirectNode and the daemon, whose XML-RPC server exports
it: plain data is what XML-RPC can carry, so both modes give exactly the same answers.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the name rules below are used where rclpy need not be imported
    from rclpy.node import Node

NamesAndTypes = list[list[Any]]  # [[name, [type, ...]], ...]


def endpoint_to_dict(info: Any) -> dict[str, Any]:
    """A TopicEndpointInfo as a dict of strings and numbers."""
    qos = info.qos_profile
    type_hash = getattr(info, 'topic_type_hash', None)
    return {
        'node_name': info.node_name,
        'node_namespace': info.node_namespace,
        'topic_type': info.topic_type,
        'topic_type_hash': str(type_hash) if type_hash is not None else 'INVALID',
        'endpoint_type': info.endpoint_type.name,
        'endpoint_gid': list(info.endpoint_gid),
        'reliability': qos.reliability.name,
        'history': qos.history.name,
        'depth': qos.depth,
        'durability': qos.durability.name,
        # rclpy's Duration prints 'Infinite' or '<n> nanoseconds', as upstream shows it.
        'lifespan': str(qos.lifespan),
        'deadline': str(qos.deadline),
        'liveliness': qos.liveliness.name,
        'liveliness_lease_duration': str(qos.liveliness_lease_duration),
    }


def matching_policies(publishers: list[dict[str, Any]]) -> tuple[str, str]:
    """(reliability, durability) a subscriber takes to get every publisher's messages (endpoint_to_dict's).

    RELIABLE only if every publisher offers it, else BEST_EFFORT; TRANSIENT_LOCAL only if every one
    does (a latched message then comes too), else VOLATILE: `ros2 topic echo`'s choice. With no
    publisher yet, the policies any later one matches: BEST_EFFORT, VOLATILE.
    """
    reliable = bool(publishers) and all(p['reliability'] == 'RELIABLE' for p in publishers)
    durable = bool(publishers) and all(p['durability'] == 'TRANSIENT_LOCAL' for p in publishers)
    return ('RELIABLE' if reliable else 'BEST_EFFORT'), ('TRANSIENT_LOCAL' if durable else 'VOLATILE')


def _plain(names_and_types: list[tuple[str, list[str]]]) -> NamesAndTypes:
    return sorted([name, list(types)] for name, types in names_and_types)


class GraphQueries:
    """Every graph question a verb asks, answered by one rclpy node."""

    def __init__(self, node: Node) -> None:
        self._node = node

    def node_names_and_namespaces(self) -> list[list[str]]:
        """Every node in the graph, as [name, namespace] pairs."""
        return [[name, ns] for name, ns in self._node.get_node_names_and_namespaces()]

    def topic_names_and_types(self) -> NamesAndTypes:
        """Every topic with its types, sorted by name: [[name, [type, ...]], ...]."""
        return _plain(self._node.get_topic_names_and_types())

    def service_names_and_types(self) -> NamesAndTypes:
        """Every service with its types, sorted by name."""
        return _plain(self._node.get_service_names_and_types())

    def action_names_and_types(self) -> NamesAndTypes:
        """Every action with its types, sorted by name."""
        from rclpy.action import get_action_names_and_types
        return _plain(get_action_names_and_types(self._node))

    def _of_node(self, query: Callable[..., list[tuple[str, list[str]]]], name: str,
                 namespace: str) -> NamesAndTypes:
        """query(name, namespace), sorted; [] for a node that left the graph since it was listed.

        A verb lists the nodes, then asks about each: a node that ends in between (another `ros2`
        process's own node, say) made rcl fail the question ("Failed to get action client names and
        type: error not set", seen under a busy suite), and the verb fail with it. A node still in
        the graph keeps its error.
        """
        from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
        try:
            return _plain(query(name, namespace))
        except (_rclpy.NodeNameNonExistentError, _rclpy.RCLError):
            if (name, namespace) in self._node.get_node_names_and_namespaces():
                raise
            return []

    def publishers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The topics the node `name` in `namespace` publishes, with their types, sorted."""
        return self._of_node(self._node.get_publisher_names_and_types_by_node, name, namespace)

    def subscribers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The topics the node subscribes to, with their types, sorted."""
        return self._of_node(self._node.get_subscriber_names_and_types_by_node, name, namespace)

    def services_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The services the node offers, with their types, sorted."""
        return self._of_node(self._node.get_service_names_and_types_by_node, name, namespace)

    def clients_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The services the node calls as a client, with their types, sorted."""
        return self._of_node(self._node.get_client_names_and_types_by_node, name, namespace)

    def action_servers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The actions the node serves, with their types, sorted."""
        from rclpy.action import get_action_server_names_and_types_by_node
        return self._of_node(partial(get_action_server_names_and_types_by_node, self._node), name,
                             namespace)

    def action_clients_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """The actions the node is a client of, with their types, sorted."""
        from rclpy.action import get_action_client_names_and_types_by_node
        return self._of_node(partial(get_action_client_names_and_types_by_node, self._node), name,
                             namespace)

    def publishers_info(self, topic: str) -> list[dict[str, Any]]:
        """Each publisher on the topic as endpoint_to_dict gives it: node, type, gid and QoS."""
        return [endpoint_to_dict(i) for i in self._node.get_publishers_info_by_topic(topic)]

    def subscriptions_info(self, topic: str) -> list[dict[str, Any]]:
        """Each subscription to the topic as endpoint_to_dict gives it: node, type, gid and QoS."""
        return [endpoint_to_dict(i) for i in self._node.get_subscriptions_info_by_topic(topic)]

    def count_publishers(self, topic: str) -> int:
        """The number of publishers on the topic, in the whole graph."""
        return self._node.count_publishers(topic)

    def count_subscribers(self, topic: str) -> int:
        """The number of subscriptions to the topic, in the whole graph."""
        return self._node.count_subscribers(topic)

    def count_clients(self, service: str) -> int:
        """The number of clients of the service, in the whole graph."""
        return self._node.count_clients(service)

    def count_services(self, service: str) -> int:
        """The number of servers of the service, in the whole graph."""
        return self._node.count_services(service)


def full_node_name(namespace: str, name: str) -> str:
    """'/' + 'talker' -> '/talker'; '/ns' + 'talker' -> '/ns/talker'."""
    return f"{namespace.rstrip('/')}/{name}"


def split_node_name(node_name: str) -> tuple[str, str]:
    """A node name (leading '/' optional) as (namespace, base name)."""
    full = node_name if node_name.startswith('/') else '/' + node_name
    namespace, _, name = full.rpartition('/')
    return namespace or '/', name


def is_hidden_node(full_name: str) -> bool:
    """Whether the node is hidden, as ros2cli hides it: its base name starts with '_'."""
    return full_name.rpartition('/')[2].startswith('_')


def is_hidden_name(name: str) -> bool:
    """A topic or service is hidden when any of its tokens starts with '_'."""
    return any(token.startswith('_') for token in name.split('/'))


def expand_topic_name(name: str) -> str:
    """Relative names resolve against the CLI node's namespace, the root."""
    return name if name.startswith('/') else '/' + name
