"""DirectNode: a hidden rclpy node of the verb itself, which waits until DDS discovery has settled."""

import argparse
import os
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from owl_common.graph import GraphQueries

from ros2cli.daemon import domain_id
from ros2cli.node.settle import (
    MOST,
    MOST_COUNTED,
    POLL,
    QUIET_COMPLETE,
    DiscoverySettling,
    graph_view,
    local_participants,
)

if TYPE_CHECKING:  # rclpy is imported when a node is made: `ros2 <command> -h` does not need it
    from rclpy.node import Node

# A verb that looks for one named entity (node, topic, service) keeps looking this much longer
# before it says "unknown": DDS discovery of a just started participant sometimes takes ~2 s.
NAMED_LOOKUP_GRACE = 2.0


def add_direct_node_arguments(parser: argparse.ArgumentParser) -> None:
    """Add --spin-time and -s/--use-sim-time, the options of a verb's own DirectNode."""
    parser.add_argument(
        '--spin-time', type=float, default=None,
        help='Spin time in seconds to wait for discovery (only applies when not using an already '
             'running daemon); by default until discovery has settled, at most '
             f'{MOST:.1f} s ({MOST_COUNTED:.1f} s while a participant of this machine is unseen)')
    parser.add_argument('-s', '--use-sim-time', action='store_true', help='Enable ROS simulation time')


def tear_down(node: 'Node', *owned: Any) -> None:
    """Destroy what a verb owns (owned first, then node) and shut rclpy down: the process ends next.

    Under owl_common's clean-up watchdog: Fast DDS can deadlock while it tears the participant down,
    and the verb must then end with every thread's stack and exit code 1, not hang until SIGKILL.
    """
    # Lazy: both import rclpy (loaded by the node's owner by now); the verbs import this module for -h.
    import rclpy
    from owl_common.run import begin_cleanup

    begin_cleanup()
    for entity in owned:
        entity.destroy()
    node.destroy_node()
    rclpy.try_shutdown()


def settle_discovery(node: 'Node', graph: GraphQueries | None = None,
                     quiet_complete: float = QUIET_COMPLETE, most: float = MOST) -> None:
    """Serve node's callbacks until discovery has settled (see ros2cli.node.settle).

    graph: node's GraphQueries, if the caller has one already; quiet_complete, most: see
    DiscoverySettling.
    """
    import rclpy  # lazy, as in tear_down

    graph = graph or GraphQueries(node)
    settling = DiscoverySettling(quiet_complete=quiet_complete, most=most)
    started = time.monotonic()
    while not settling.settled(time.monotonic() - started, *graph_view(graph, local_participants())):
        rclpy.spin_once(node, timeout_sec=POLL)


class DirectNode:
    """Owns rclpy for the verb: init on creation, shutdown on close()."""

    def __init__(self, args: argparse.Namespace | None = None, node_name: str | None = None,
                 spin_time: float | None = None) -> None:
        # Lazy: rclpy is slow to import, and `ros2 <command> -h` imports this module (through the verbs).
        import rclpy
        from rclpy.node import Node
        from rclpy.parameter import Parameter

        self._rclpy = rclpy
        use_sim_time = bool(getattr(args, 'use_sim_time', False))
        if spin_time is None:
            spin_time = getattr(args, 'spin_time', None)
        domain_id()  # one line for a domain no node can use, before Fast DDS prints its own log lines
        rclpy.init(args=[])
        # Without the type description service nobody asks this hidden node for: its service type
        # is what would load numpy (service_msgs' fixed array), half of the node's 0.1 s start.
        self.node = Node(
            node_name or f'_ros2cli_{os.getpid()}', start_parameter_services=False,
            parameter_overrides=[Parameter('use_sim_time', value=use_sim_time),
                                 Parameter('start_type_description_service', value=False)])
        self._graph: GraphQueries | None = None
        if spin_time is None:
            settle_discovery(self.node, self.graph)
        else:
            self.spin_for(spin_time)

    def spin_for(self, seconds: float) -> None:
        """Serve callbacks for that long; what DDS discovery needs to fill the graph cache."""
        deadline = time.monotonic() + max(0.0, seconds)
        while (remaining := deadline - time.monotonic()) > 0:
            self._rclpy.spin_once(self.node, timeout_sec=min(remaining, 0.05))

    def wait_until(self, condition: Callable[[], bool], timeout: float) -> bool:
        """Spin until condition() holds (True) or timeout seconds have passed (False)."""
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() >= deadline:
                return False
            self.spin_for(0.05)
        return True

    @property
    def graph(self) -> 'GraphQueries':
        """The node's graph queries (GraphQueries, made on first use)."""
        if self._graph is None:
            self._graph = GraphQueries(self.node)
        return self._graph

    def close(self) -> None:
        """Destroy the node and shut rclpy down (see tear_down); the process is meant to end next."""
        tear_down(self.node)

    def __enter__(self) -> 'DirectNode':
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
