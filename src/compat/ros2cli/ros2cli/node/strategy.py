"""NodeStrategy: ask the daemon when it runs, else a DirectNode (and start the daemon for next time)."""

import argparse
import time
from collections.abc import Callable
from typing import Any

from owl_humble.launcher import ensure_discovery_bridge

from ros2cli.node.direct import NAMED_LOOKUP_GRACE, DirectNode, add_direct_node_arguments
from ros2cli.node.graph import Graph
from ros2cli.node.settle import MOST, POLL, QUIET_COMPLETE, DiscoverySettling

# A daemon up this long has seen every repair of lost discovery data (each within about 1 s).
DAEMON_SETTLED = 5.0


def add_strategy_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the DirectNode options and --no-daemon: the options of every verb that uses a NodeStrategy."""
    add_direct_node_arguments(parser)
    parser.add_argument('--no-daemon', action='store_true',
                        help='Do not spawn nor use an already running daemon')


class NodeStrategy:
    """`.graph` answers graph queries; `.direct` is a DirectNode for everything else (lazy)."""

    def __init__(self, args: argparse.Namespace, spin_time: float | None = None) -> None:
        self._args = args
        self._spin_time = spin_time
        self._direct: DirectNode | None = None
        # Not upstream's: the nodes of Humble modules reach our graph through this bridge.
        ensure_discovery_bridge()
        graph: Graph | None = None
        if not getattr(args, 'no_daemon', False):
            # Lazy, and only here: neither `-h` (the verbs import this module) nor --no-daemon needs it.
            from ros2cli.daemon import client

            if client.is_daemon_running():
                daemon = client.DaemonGraph()
                graph = daemon
                wait_until_settled(daemon)
            else:
                client.spawn_daemon(on_demand=True)
        self.graph: Graph = self.direct.graph if graph is None else graph

    @property
    def uses_daemon(self) -> bool:
        """True when .graph is the daemon's (a warm cache), False when it is the verb's own DirectNode."""
        return self._direct is None or self.graph is not self._direct.graph

    def wait_until(self, condition: Callable[[], bool], timeout: float = NAMED_LOOKUP_GRACE) -> bool:
        """condition() now, or after up to timeout more seconds of discovery (DirectNode only).

        The daemon's cache is warm already, so a miss there is final.
        """
        if self.uses_daemon:
            return condition()
        return self.direct.wait_until(condition, timeout)

    @property
    def direct(self) -> DirectNode:
        """The verb's own DirectNode, made (and discovery waited for) on first use."""
        if self._direct is None:
            self._direct = DirectNode(self._args, spin_time=self._spin_time)
        return self._direct

    def close(self) -> None:
        """Close the DirectNode if one was made; a daemon is left running."""
        if self._direct is not None:
            self._direct.close()

    def __enter__(self) -> 'NodeStrategy':
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def wait_until_settled(daemon: Any) -> None:
    """Wait, as a verb's own node does, until a young daemon's graph has settled (ros2cli.node.settle).

    A daemon started a moment ago (by `ros2 daemon start` or the previous call) may still be
    discovering. Past MOST s of age a complete graph is answered at once (what trickles in right
    after a participant is seen has arrived by then); one up for DAEMON_SETTLED s is not asked at
    all.
    """
    from ros2cli.daemon.client import DaemonFault  # lazy: as in NodeStrategy (loaded by then)

    uptime = daemon.get_uptime()
    if uptime >= DAEMON_SETTLED:
        return
    settling = DiscoverySettling(quiet_complete=0.0 if uptime >= MOST else QUIET_COMPLETE)
    started = time.monotonic()
    try:
        while not settling.settled(time.monotonic() - started, *daemon.discovery_view()):
            time.sleep(POLL)
    except DaemonFault:
        pass  # a daemon of an older install, started before an update: its graph as it is
