"""When a participant that just joined the ROS graph has seen it: discovery has settled.

A verb's own node (or a daemon started a moment ago) learns the graph piece by piece: the other
processes' DDS participants, then their endpoints, then their node names. Upstream waits a fixed
0.5 s, which is often too short and always too long for a graph found in 0.1 s: each process
answers a newcomer's first announcement, but a lost answer is only made good by its next periodic
announcement (0.5 s apart, config/fastdds.xml) and lost endpoint data by Fast DDS's 1 s heartbeat,
so one turtle of two could be missing half a second after the other was listed. (The venv
repairs why answers were lost, owl_fastdds_enable_order.c; the wait below still covers lost
endpoint data and any other Fast DDS build.)

With ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (how Owl Kit Lab runs unless a network is chosen)
every participant of the domain is a process of this machine, bound to a discovery port that
/proc/net/udp shows. The answer is given once as many participants have been seen (through the
endpoints of their nodes) as there are such ports, every endpoint's node is named, and nothing has
changed for QUIET_COMPLETE s; while a participant bound here is still unseen, the answer waits for
it up to MOST_COUNTED s (on a loaded machine a lost announcement can be repaired later than MOST).
A complete graph that keeps changing is answered MOST s after it became complete: a participant
seen late (one held up while the asker joined) sends its endpoints late too. Elsewhere (other hosts
can take part) it is given once a node that is not a hidden one is in sight and nothing has changed
for QUIET s. A graph that never gets there is answered at MOST s.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterator
from typing import TYPE_CHECKING, Any

from owl_common.ros_env import discovery_range, domain_id, static_peers

if TYPE_CHECKING:
    from ros2cli.node.graph import Graph

QUIET = 0.25  # s without a change, once another node is in sight (participants not countable)
QUIET_COMPLETE = 0.05  # s without a change once every local participant is seen
MOST = 1.2  # s: the answer then, whatever has arrived (lost endpoint data is repaired after 1 s)
MOST_COUNTED = 3.0  # s: the bound while a participant that /proc/net/udp shows has not been seen
POLL = 0.02  # s between two looks at the graph
# rmw_fastrtps's LOCALHOST discovery reaches participants 0..31 of a domain (maxInitialPeersRange);
# participant i listens for discovery on port 7410 + 250 * domain + 2 * i (the RTPS port formula).
LOCAL_PARTICIPANTS = 32
UNKNOWN_NODE = '_NODE_NAME_UNKNOWN_'  # rmw's node name for an endpoint whose node is not yet known


class DiscoverySettling:
    """Feed it what the graph looks like at growing elapsed times; it says when to answer."""

    def __init__(self, quiet: float = QUIET, quiet_complete: float = QUIET_COMPLETE,
                 most: float = MOST, most_counted: float = MOST_COUNTED) -> None:
        self.quiet = quiet
        self.quiet_complete = quiet_complete
        self.most = most
        self.most_counted = most_counted
        self._seen: Hashable = None
        self._changed_at = 0.0
        self._complete_since: float | None = None

    def settled(self, elapsed: float, graph: Hashable, others_seen: bool, complete: bool | None) -> bool:
        """Whether to answer now, elapsed s after joining.

        graph is any value that changes when the graph does; others_seen whether a node other than
        a hidden one is in it; complete whether every participant there is has been seen, or None
        where that cannot be known.
        """
        if graph != self._seen:
            self._seen = graph
            self._changed_at = elapsed
        quiet_for = elapsed - self._changed_at
        if complete is True:
            if self._complete_since is None:
                self._complete_since = elapsed
            bound = self._complete_since + self.most
        else:
            self._complete_since = None
            bound = self.most_counted if complete is False else self.most
        if elapsed >= bound:
            return True
        if complete is None:
            return others_seen and quiet_for >= self.quiet
        return complete and quiet_for >= self.quiet_complete


def bound_discovery_ports(domain_id: int, proc_net_udp: str) -> int:
    """How many participants of the domain listen on this machine, from /proc/net/udp's text."""
    base = 7410 + 250 * domain_id
    wanted = {base + 2 * index for index in range(LOCAL_PARTICIPANTS)}
    bound = set()
    for line in proc_net_udp.splitlines()[1:]:
        fields = line.split()
        if len(fields) > 1 and ':' in fields[1]:
            port = int(fields[1].rsplit(':', 1)[1], 16)
            if port in wanted:
                bound.add(port)
    return len(bound)


def local_participants() -> int | None:
    """Participants of this shell's domain on this machine, or None when others can take part."""
    if discovery_range() != 'LOCALHOST' or static_peers():
        return None
    try:
        domain = domain_id()
        with open('/proc/net/udp', encoding='ascii') as table:
            return bound_discovery_ports(domain, table.read())
    except (OSError, ValueError):
        return None


def graph_endpoints(graph: Graph) -> Iterator[dict[str, Any]]:
    """Every publisher and subscription in the graph, as rclpy's endpoint info dicts."""
    for topic, _ in graph.topic_names_and_types():
        yield from graph.publishers_info(topic)
        yield from graph.subscriptions_info(topic)


def graph_view(graph: Graph, participants: int | None) -> tuple[Hashable, bool, bool | None]:
    """(graph, others_seen, complete) of a graph: what DiscoverySettling.settled() takes after elapsed.

    graph is what settling compares (node, topic and service names); others_seen whether a node
    that is not a hidden one (the asker's own, a `ros2` daemon) is in sight; complete whether all
    of `participants` are seen (None when participants is None).
    """
    nodes = tuple(sorted(f'{namespace.rstrip("/")}/{name}'
                         for name, namespace in graph.node_names_and_namespaces()))
    topics = tuple(sorted(name for name, _ in graph.topic_names_and_types()))
    services = tuple(sorted(name for name, _ in graph.service_names_and_types()))
    others = any(not node.rsplit('/', 1)[-1].startswith('_') for node in nodes)
    complete = None
    if participants is not None:
        endpoints = list(graph_endpoints(graph))
        seen = {tuple(info['endpoint_gid'][:12]) for info in endpoints}
        complete = len(seen) >= participants and all(info['node_name'] != UNKNOWN_NODE for info in endpoints)
    return (nodes, topics, services), others, complete
