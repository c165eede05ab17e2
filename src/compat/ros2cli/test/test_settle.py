from ros2cli.daemon.server import keeps_company
from ros2cli.node.settle import (
    MOST,
    MOST_COUNTED,
    QUIET,
    QUIET_COMPLETE,
    UNKNOWN_NODE,
    DiscoverySettling,
    bound_discovery_ports,
    graph_view,
)

STEP = 0.02


def ticks(until: float = 3.5) -> list[float]:
    return [round(i * STEP, 3) for i in range(int(until / STEP) + 1)]


def first_tick_quiet(changed: float, quiet: float) -> float:
    """The first tick at which the graph, last changed at changed, has been quiet for quiet s."""
    return min(t for t in ticks() if t - changed >= quiet)


def answered_at(timeline: list[tuple[float, str, bool, bool | None]]) -> float | None:
    """The first elapsed time at which a fresh DiscoverySettling answers, fed the timeline in turn."""
    settling = DiscoverySettling()
    for elapsed, graph, others, complete in timeline:
        if settling.settled(elapsed, graph, others, complete):
            return elapsed
    return None


def test_every_local_participant_seen_is_answered_after_a_short_quiet():
    timeline = [(t, 'all' if t >= 0.1 else 'self', t >= 0.1, t >= 0.1) for t in ticks()]
    assert answered_at(timeline) == first_tick_quiet(0.1, QUIET_COMPLETE)


def test_a_participant_still_missing_holds_the_answer_whatever_the_quiet():
    # One turtle seen at 0.1 s, the other only at its next announcement, 0.6 s.
    def graph(t: float) -> tuple[str, bool]:
        if t < 0.1:
            return 'self', False
        return ('one turtle', False) if t < 0.6 else ('two turtles', True)
    timeline = [(t, graph(t)[0], t >= 0.1, graph(t)[1]) for t in ticks()]
    assert answered_at(timeline) == first_tick_quiet(0.6, QUIET_COMPLETE)


def test_where_participants_cannot_be_counted_a_quiet_window_after_the_first_node_decides():
    def graph(t: float) -> str:  # each change within the quiet window of the last
        return 'one' if t < 0.2 else 'two' if t < 0.4 else 'three'
    timeline = [(t, graph(t), True, None) for t in ticks()]
    assert answered_at(timeline) == first_tick_quiet(0.4, QUIET)


def test_nothing_but_itself_is_believed_only_at_the_bound():
    assert answered_at([(t, 'self', False, None) for t in ticks()]) == MOST


def test_a_participant_bound_here_but_unseen_is_waited_for_up_to_the_longer_bound():
    assert answered_at([(t, 'self', False, False) for t in ticks()]) == MOST_COUNTED
    # A loaded machine: the second turtle's announcement repaired at 2.1 s, past MOST, is answered
    # after the short quiet once it is seen.
    timeline = [(t, 'one' if t < 2.1 else 'two', True, t >= 2.1) for t in ticks()]
    assert answered_at(timeline) == first_tick_quiet(2.1, QUIET_COMPLETE)


def test_a_graph_that_never_stops_changing_is_answered_at_the_bound():
    assert answered_at([(t, str(t), True, True) for t in ticks()]) == MOST
    assert answered_at([(t, str(t), True, None) for t in ticks()]) == MOST
    # Complete only from 0.8 s (a participant held up while the asker joined): MOST from then.
    assert answered_at([(t, str(t), True, t >= 0.8) for t in ticks()]) == 0.8 + MOST


def test_a_participant_seen_late_is_given_time_for_the_rest_of_its_endpoints():
    # A listener held up until 0.76 s is seen at 0.8 s; on a busy machine its endpoints then arrive
    # one by one, 0.04 s apart, the last (its subscription) at 1.4 s, past MOST from the start.
    def graph(t: float) -> str:
        return 'self' if t < 0.8 else str(min(int(round((t - 0.8) / 0.04, 6)), 15))
    timeline = [(t, graph(t), t >= 0.8, t >= 0.8) for t in ticks()]
    assert answered_at(timeline) == first_tick_quiet(1.4, QUIET_COMPLETE)


PROC_NET_UDP = """   sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid
  966: 00000000:1CF2 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        0 1 2 0 0
  967: 00000000:1CF3 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        0 2 2 0 0
  968: 00000000:1CF4 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        0 3 2 0 0
  969: 0100007F:1CF4 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        0 4 2 0 0
  970: 00000000:1DEC 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        0 5 2 0 0
"""


def test_discovery_ports_are_counted_per_domain():
    # Domain 0: 7410 (0x1CF2) and 7412 (0x1CF4, bound twice) are participants 0 and 1; 7411 is
    # participant 0's data port. Domain 1's participant 0 listens on 7660 (0x1DEC).
    assert bound_discovery_ports(0, PROC_NET_UDP) == 2
    assert bound_discovery_ports(1, PROC_NET_UDP) == 1
    assert bound_discovery_ports(2, PROC_NET_UDP) == 0


class Graph:
    def __init__(self, nodes: list[list[str]], endpoints: list[dict[str, object]]) -> None:
        self.nodes = nodes
        self.endpoints = endpoints

    def node_names_and_namespaces(self) -> list[list[str]]:
        return self.nodes

    def topic_names_and_types(self) -> list[list[object]]:
        return [['/rosout', ['rcl_interfaces/msg/Log']]]

    def service_names_and_types(self) -> list[list[object]]:
        return []

    def publishers_info(self, topic: str) -> list[dict[str, object]]:
        return self.endpoints

    def subscriptions_info(self, topic: str) -> list[dict[str, object]]:
        return []


def endpoint(participant: int, node: str) -> dict[str, object]:
    return {'endpoint_gid': [participant] * 12 + [0, 0, 1, 3], 'node_name': node}


def test_the_view_counts_participants_by_their_endpoints_and_waits_for_node_names():
    hidden = [['_ros2cli_1234', '/'], ['_ros2cli_daemon_7_ab', '/']]
    view = graph_view(Graph(hidden, [endpoint(1, '_ros2cli_1234')]), participants=2)
    assert view[1:] == (False, False)
    both = Graph([*hidden, ['turtle1', '/']], [endpoint(1, '_ros2cli_1234'), endpoint(2, 'turtle1')])
    assert graph_view(both, participants=2)[1:] == (True, True)
    unnamed = Graph(both.nodes, [endpoint(1, '_ros2cli_1234'), endpoint(2, UNKNOWN_NODE)])
    assert graph_view(unnamed, participants=2)[1:] == (True, False)
    assert graph_view(both, participants=None)[1:] == (True, None)
    lone = Graph([["turtlesim", "/turtle2"]], [])
    assert graph_view(lone, None)[0][0] == ("/turtle2/turtlesim",)


def test_only_a_node_with_endpoints_keeps_an_alone_exiting_daemon_company():
    own = ['_ros2cli_daemon_7_ab', '/']
    assert not keeps_company(Graph([own], [endpoint(1, '_ros2cli_daemon_7_ab')]))
    ghost = Graph([own, ['talker', '/']], [endpoint(1, '_ros2cli_daemon_7_ab')])  # listed, no endpoint
    assert not keeps_company(ghost)
    assert keeps_company(Graph([own, ['talker', '/']], [endpoint(2, 'talker')]))
    assert keeps_company(Graph([own], [endpoint(2, UNKNOWN_NODE)]))  # a node not yet named is someone
