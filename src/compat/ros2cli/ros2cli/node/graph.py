"""Graph: what a verb asks of the ROS graph, answered by the daemon or by a verb's own node.

The daemon answers through DaemonGraph (over XML-RPC), a verb's own node through
owl_common.graph.GraphQueries. Both give the same plain answers.
"""

from typing import Any, Protocol

NamesAndTypes = list[list[Any]]  # [[name, [type, ...]], ...] (XML-RPC turns tuples into lists)


class Graph(Protocol):
    """The graph queries a verb may make; DaemonGraph and GraphQueries both answer them."""

    def node_names_and_namespaces(self) -> list[list[str]]:
        """[name, namespace] of every node in the graph, hidden ones included."""
        ...

    def topic_names_and_types(self) -> NamesAndTypes:
        """[name, [type, ...]] of every topic, sorted by name."""
        ...

    def service_names_and_types(self) -> NamesAndTypes:
        """[name, [type, ...]] of every service, sorted by name."""
        ...

    def action_names_and_types(self) -> NamesAndTypes:
        """[name, [type, ...]] of every action, sorted by name."""
        ...

    def publishers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[topic, [type, ...]] of the topics the node (base name, namespace) publishes."""
        ...

    def subscribers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[topic, [type, ...]] of the topics the node subscribes to."""
        ...

    def services_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[service, [type, ...]] of the services the node serves."""
        ...

    def clients_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[service, [type, ...]] of the services the node has clients of."""
        ...

    def action_servers_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[action, [type, ...]] of the actions the node serves."""
        ...

    def action_clients_by_node(self, name: str, namespace: str) -> NamesAndTypes:
        """[action, [type, ...]] of the actions the node has clients of."""
        ...

    def publishers_info(self, topic: str) -> list[dict[str, Any]]:
        """A dict per publisher of the topic: node, type, GID and QoS (owl_common.graph.endpoint_to_dict)."""
        ...

    def subscriptions_info(self, topic: str) -> list[dict[str, Any]]:
        """A dict per subscription of the topic, as publishers_info gives them."""
        ...

    def count_publishers(self, topic: str) -> int:
        """How many publishers the topic has."""
        ...

    def count_subscribers(self, topic: str) -> int:
        """How many subscriptions the topic has."""
        ...

    def count_clients(self, service: str) -> int:
        """How many clients the service has."""
        ...

    def count_services(self, service: str) -> int:
        """How many servers the service has."""
        ...
