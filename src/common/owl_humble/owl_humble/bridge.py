"""discovery_bridge: Humble's (and other installs') node names for our tools, in our layout.

Our processes keep their graph messages (ros_discovery_info) in a partition of their own
(config/fastdds.xml), so no Humble module ever reads one in its 24-byte-gid layout. This process
is how the graph still reaches them: it reads the graph messages of the default partition (Humble
modules; also any ROS 2 install without our profile), rewrites each in the 16-byte-gid layout and
publishes it in our partition, one writer per participant, so every rmw of ours (the `ros2`
command, its daemon, rqt, `owl check`, a student's node) knows those nodes as it knows its own.
When a participant leaves, its entry is emptied and its writer deleted, so the nodes disappear
at once and a process that starts later never hears of them.

One bridge runs per user, ROS domain and discovery range; `owl_humble.launcher` starts it on
demand. It exits once none of our processes has been in its domain for ALONE_TIMEOUT seconds.
"""

from __future__ import annotations

import argparse
import os
import signal
import socket
import sys
import time
from types import FrameType

from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsParticipant, BuiltinTopicDcpsPublication
from cyclonedds.core import InstanceState, Policy, Qos
from cyclonedds.pub import DataWriter

from owl_humble import discovery_info as info
from owl_humble import wire
from owl_humble.graph_partition import DISCOVERY_TOPIC, JAZZY_GRAPH_PARTITION

ALONE_TIMEOUT = 10.0  # seconds
POLL_PERIOD = 0.02  # seconds between looks at the graph messages


class DiscoveryBridge:
    """Forwards Humble participants' graph messages into our partition, one writer per participant."""

    def __init__(self, participant: wire.Participant) -> None:
        self.participant = participant
        self.reader = participant.reader(
            DISCOVERY_TOPIC, wire.DISCOVERY_TYPE, wire.discovery_reader_qos())
        self.participants = BuiltinDataReader(participant.dds, BuiltinTopicDcpsParticipant)
        self.publications = BuiltinDataReader(participant.dds, BuiltinTopicDcpsPublication)
        self.writers: dict[bytes, DataWriter] = {}
        self.ours: set[bytes] = set()  # keys of our processes' graph writers (the partition's)
        self.last_seen_ours = time.monotonic()

    def step(self) -> None:
        """One look at the graph: forward new messages, forget participants that left, note ours."""
        for sample in wire.take(self.reader):
            if sample.alive:
                self.forward(sample.data)
        for participant in self.participants.take(64):
            state = participant.sample_info.instance_state
            if state != InstanceState.Alive:
                self.forget(participant.key.bytes)
        for publication in self.publications.take(256):
            if publication.sample_info.instance_state != InstanceState.Alive:
                self.ours.discard(publication.key.bytes)
            elif publication.topic_name == DISCOVERY_TOPIC and self._in_our_partition(publication.qos):
                self.ours.add(publication.key.bytes)
        if self.ours:
            self.last_seen_ours = time.monotonic()

    @staticmethod
    def _in_our_partition(qos: Qos) -> bool:
        partition = qos[Policy.Partition] if Policy.Partition in qos else None
        return partition is not None and JAZZY_GRAPH_PARTITION in partition.partitions

    def forward(self, data: bytes) -> None:
        """Publish a graph message in our partition, in Jazzy's layout (not an unreadable one or our own)."""
        layout = info.layout_of(data)
        if layout is None:
            return
        entities = info.decode(data, layout).in_layout(info.Layout.JAZZY)
        if entities.gid == self.participant.gid:
            return
        writer = self.writers.get(entities.gid)
        if writer is None:
            writer = self.participant.writer(DISCOVERY_TOPIC, wire.DISCOVERY_TYPE,
                                             wire.discovery_writer_qos(), JAZZY_GRAPH_PARTITION)
            self.writers[entities.gid] = writer
        wire.write(writer, info.encode(entities, info.Layout.JAZZY))

    def forget(self, gid: bytes) -> None:
        """Empty and delete the writer of a participant that left, so our tools drop its nodes at once."""
        writer = self.writers.pop(gid, None)
        if writer is not None:
            # Emptied first: a process whose DDS has not yet seen the participant leave drops its nodes.
            wire.write(writer, info.encode(info.ParticipantEntities(gid), info.Layout.JAZZY))
            writer.__del__()

    def alone_for(self) -> float:
        """Seconds since a step last saw a graph writer of our processes (or since the bridge started)."""
        return time.monotonic() - self.last_seen_ours


def main(argv: list[str] | None = None) -> None:
    """The discovery_bridge command: bridge until SIGINT/SIGTERM or --alone-timeout s alone, then exit 0."""
    parser = argparse.ArgumentParser(
        prog='discovery_bridge',
        description="Shows Humble modules' nodes to our tools (see owl_humble/bridge.py).")
    parser.add_argument('--fd', type=int, help='the singleton socket the launcher bound (kept open)')
    parser.add_argument('--alone-timeout', type=float, default=ALONE_TIMEOUT,
                        help='exit after this many seconds without any of our processes (default 10)')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    singleton = socket.socket(fileno=args.fd) if args.fd is not None else None
    stopping: list[int] = []

    def stop(signum: int, _frame: FrameType | None) -> None:
        stopping.append(signum)

    signal.signal(signal.SIGINT, stop)
    signal.signal(signal.SIGTERM, stop)
    bridge = DiscoveryBridge(wire.Participant())
    while not stopping and bridge.alone_for() < args.alone_timeout:
        bridge.step()
        time.sleep(POLL_PERIOD)
    for gid in list(bridge.writers):
        bridge.forget(gid)
    if singleton is not None:
        singleton.close()
    os._exit(0)  # Cyclone's threads need no orderly goodbye: the participant's leaving is announced above


if __name__ == '__main__':
    main()
