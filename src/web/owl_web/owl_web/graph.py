"""The ROS graph as our pages show it: one node-free model and the 'graph' channel that pushes it.

The model is build_model's; the channel (GraphChannel) pushes it to every subscribed page when it
changes.

Like rqt_graph's "Nodes/Topics (all)" view: a box per node and per topic, an arrow from a
publishing node to its topic and from a topic to each subscribing node. The page lays it out.
"""

import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from owl_common.graph import GraphQueries, full_node_name, is_hidden_name, is_hidden_node
from rclpy.node import Node

from owl_web import codec
from owl_web.server import Subscription, WebServer

# rqt_graph hides these by default ("Debug" and "Params" in its Hide box).
DEBUG_TOPICS = frozenset({'/rosout', '/rosout_agg', '/parameter_events', '/statistics'})
# s between two looks at the node's graph cache while a page watches it (rclpy offers no graph
# event to wait for; a look reads local memory, no network: well under a millisecond here).
GRAPH_CHECK_PERIOD = 0.1
SUBSCRIBE_KEYS = ('hide_debug', 'hide_leaf_topics')

TopicsAndTypes = list[tuple[str, list[str]]]
Endpoints = dict[str, tuple[TopicsAndTypes, TopicsAndTypes]]  # node -> (published, subscribed)


@dataclass
class GraphModel:
    """Visible nodes and topics (full names) and the arrows between them."""

    nodes: list[str] = field(default_factory=list)
    topics: dict[str, list[str]] = field(default_factory=dict)  # topic -> types
    edges: list[tuple[str, str]] = field(default_factory=list)  # (from, to), names of boxes

    def as_json(self) -> dict[str, Any]:
        """The model as a page gets it: node names, topics with their types, edges as from/to pairs."""
        return {'nodes': self.nodes,
                'topics': [{'name': name, 'types': types} for name, types in self.topics.items()],
                'edges': [{'from': source, 'to': target} for source, target in self.edges]}


def build_model(endpoints: Endpoints, hide_debug: bool = True, hide_leaf_topics: bool = False,
                own_node: str | None = None) -> GraphModel:
    """The graph to draw from {node: (published [(topic, types)], subscribed [(topic, types)])}.

    hide_debug (rqt_graph's "Debug", on by default there too) hides /rosout, /parameter_events
    and hidden nodes and topics (a name part starting with '_', e.g. `ros2 topic pub`'s
    /_ros2cli_1234 node); hide_leaf_topics hides topics with only publishers or only subscribers.
    own_node, the drawing page's own node, shows only while it has a topic shown (rqt's Message
    Publisher publishing, its Image View subscribed): a box of its own would say nothing.
    """
    def shown(name: str, is_hidden: Callable[[str], bool]) -> bool:
        return not hide_debug or not (is_hidden(name) or name in DEBUG_TOPICS)

    publishers: dict[str, set[str]] = {}
    subscribers: dict[str, set[str]] = {}
    types: dict[str, set[str]] = {}
    nodes = sorted(node for node in endpoints if shown(node, is_hidden_node))
    for node in nodes:
        published, subscribed = endpoints[node]
        for side, entries in ((publishers, published), (subscribers, subscribed)):
            for topic, topic_types in entries:
                if not shown(topic, is_hidden_name):
                    continue
                side.setdefault(topic, set()).add(node)
                types.setdefault(topic, set()).update(topic_types)
    topics = sorted(types)
    if hide_leaf_topics:
        topics = [t for t in topics if publishers.get(t) and subscribers.get(t)]
    if own_node in nodes and not any(own_node in publishers.get(t, ()) or own_node in subscribers.get(t, ())
                                     for t in topics):
        nodes.remove(own_node)
    model = GraphModel(nodes=nodes, topics={t: sorted(types[t]) for t in topics})
    for topic in topics:
        model.edges += [(node, topic) for node in sorted(publishers.get(topic, ()))]
        model.edges += [(topic, node) for node in sorted(subscribers.get(topic, ()))]
    return model


def read_endpoints(queries: GraphQueries) -> Endpoints:
    """Every node's published and subscribed topics."""
    endpoints: Endpoints = {}
    for name, namespace in queries.node_names_and_namespaces():
        full_name = full_node_name(namespace, name)
        try:
            published = queries.publishers_by_node(name, namespace)
            subscribed = queries.subscribers_by_node(name, namespace)
        except RuntimeError:  # the node left between the two questions
            continue
        endpoints[full_name] = ([(topic, list(types)) for topic, types in published],
                                [(topic, list(types)) for topic, types in subscribed])
    return endpoints


def graph_options(params: dict[str, Any]) -> tuple[bool, bool]:
    """(hide_debug, hide_leaf_topics) of a subscription or request; rqt_graph's defaults."""
    codec.check_keys(params, SUBSCRIBE_KEYS)
    return (codec.boolean(params.get('hide_debug', True), 'hide_debug'),
            codec.boolean(params.get('hide_leaf_topics', False), 'hide_leaf_topics'))


class GraphChannel:
    """The 'graph' channel of a server: a page gets the model at once and again at every change.

    A page subscribes with {"channel": "graph", "hide_debug": true, "hide_leaf_topics": false}.
    """

    def __init__(self, node: Node, server: WebServer) -> None:
        self._queries = GraphQueries(node)
        self._own_name = node.get_fully_qualified_name()
        self._lock = threading.Lock()
        self._watchers: dict[Subscription, tuple[tuple[bool, bool], dict[str, Any] | None]] = {}
        self._endpoints: Endpoints | None = None
        server.channel('graph', self._open, self._close)
        self._timer = node.create_timer(GRAPH_CHECK_PERIOD, self._check)

    def model(self, hide_debug: bool, hide_leaf_topics: bool) -> GraphModel:
        """The graph as it is now for the given options (the server's own node while it has a topic shown)."""
        return build_model(read_endpoints(self._queries), hide_debug, hide_leaf_topics, self._own_name)

    def _open(self, subscription: Subscription) -> None:
        options = graph_options(subscription.params)
        with self._lock:
            self._watchers[subscription] = (options, None)
        self._push(read_endpoints(self._queries), force=True)

    def _close(self, subscription: Subscription) -> None:
        with self._lock:
            self._watchers.pop(subscription, None)

    def _check(self) -> None:
        with self._lock:
            if not self._watchers:
                return
        self._push(read_endpoints(self._queries))

    def _push(self, endpoints: Endpoints, force: bool = False) -> None:
        """Send each watcher its view of the graph if it differs from what it has."""
        with self._lock:
            if endpoints == self._endpoints and not force:
                return
            self._endpoints = endpoints
            for subscription, (options, sent) in list(self._watchers.items()):
                model = build_model(endpoints, *options, own_node=self._own_name).as_json()
                if model != sent:
                    self._watchers[subscription] = (options, model)
                    subscription.send(model)
