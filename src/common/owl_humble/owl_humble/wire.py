"""A DDS participant that speaks to ROS 2 as Humble does, on Eclipse Cyclone DDS (from PyPI).

rclpy cannot be made to send Humble's discovery layout or leave out Jazzy's type hashes, so the
Humble side of the wire uses a second DDS library. Samples are read and written as serialized
bytes: rclpy's serializer makes the ROS messages (same layout on both distributions) and
`discovery_info` the graph messages, so no message is defined twice.

Cyclone sends type information with its endpoints; Fast DDS ignores it and matches on the type
name, and our Cyclone peers all use the one opaque type per name made here, so they match too.
Fast DDS sends no type information, and Cyclone then matches on the name as well.
"""

from __future__ import annotations

import types
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from cyclonedds._clayer import ddspy_take, ddspy_write
from cyclonedds.core import InstanceState, Policy, Qos, SampleState, ViewState
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import uint8
from cyclonedds.pub import DataWriter, Publisher
from cyclonedds.sub import DataReader, Subscriber
from cyclonedds.topic import Topic
from owl_common.ros_env import discovery_range, domain_id, static_peers

DISCOVERY_TYPE = 'rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_'
SECOND = 1_000_000_000
ANY_SAMPLE = SampleState.Any | ViewState.Any | InstanceState.Any


def cyclone_config(discovery_range: str, static_peers: list[str]) -> str | None:
    """Cyclone's configuration for ROS 2's discovery range (None: Cyclone's own defaults)."""
    peers = ''.join(f'<Peer address="{peer}"/>' for peer in static_peers)
    if discovery_range == 'LOCALHOST':
        # As rmw_fastrtps does it: loopback only, unicast to the well-known ports of each index.
        return ('<CycloneDDS><Domain Id="any"><General><Interfaces><NetworkInterface address="127.0.0.1"/>'
                '</Interfaces><AllowMulticast>false</AllowMulticast></General><Discovery>'
                '<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>120</MaxAutoParticipantIndex>'
                f'<Peers><Peer address="127.0.0.1"/>{peers}</Peers></Discovery></Domain></CycloneDDS>')
    if peers:
        return (f'<CycloneDDS><Domain Id="any"><Discovery><Peers>{peers}</Peers></Discovery>'
                '</Domain></CycloneDDS>')
    return None


def ros_discovery_settings(environ: dict[str, str] | None = None) -> tuple[int, str, list[str]]:
    """ROS_DOMAIN_ID, ROS_AUTOMATIC_DISCOVERY_RANGE and ROS_STATIC_PEERS as rcl reads them."""
    return domain_id(environ), discovery_range(environ), static_peers(environ)


_opaque_types: dict[str, type] = {}


def opaque_type(typename: str) -> type:
    """An IDL type named like the ROS type, whose samples we only ever handle as bytes.

    Cyclone checks a sample against the type's first members when it is written or received and
    keeps the bytes whole: one octet accepts any ROS message in either layout.
    """
    if typename not in _opaque_types:
        body = types.new_class(
            typename.replace(':', '_'), (IdlStruct,), {'typename': typename},
            lambda namespace: namespace.update({'__annotations__': {'first_octet': uint8}}))
        _opaque_types[typename] = dataclass(body)
    return _opaque_types[typename]


def discovery_writer_qos() -> Qos:
    """The QoS of a ros_discovery_info writer: reliable, transient local, the last sample only."""
    return Qos(Policy.Reliability.Reliable(max_blocking_time=SECOND), Policy.Durability.TransientLocal,
               Policy.History.KeepLast(1))


def discovery_reader_qos() -> Qos:
    """The QoS of a ros_discovery_info reader: reliable, transient local, every sample kept."""
    return Qos(Policy.Reliability.Reliable(max_blocking_time=SECOND), Policy.Durability.TransientLocal,
               Policy.History.KeepAll)


def topic_qos(depth: int = 10) -> Qos:
    """Rclpy's QoSProfile(depth): reliable, volatile."""
    return Qos(Policy.Reliability.Reliable(max_blocking_time=SECOND), Policy.Durability.Volatile,
               Policy.History.KeepLast(depth))


@dataclass
class RawSample:
    """A taken sample as serialized bytes; alive is False for one without data (an instance that left)."""

    data: bytes
    alive: bool


class Participant:
    """One DDS participant in the ROS domain and discovery range of the environment."""

    def __init__(self, environ: dict[str, str] | None = None) -> None:
        domain, discovery_range, peers = ros_discovery_settings(environ)
        config = cyclone_config(discovery_range, peers)
        self.domain_id = domain
        self._domain = Domain(domain, config) if config else None
        self.dds = DomainParticipant(domain)
        self._topics: dict[str, Topic] = {}

    @property
    def gid(self) -> bytes:
        """The participant's GUID, 16 bytes (prefix and entity id), as rmw makes its gid."""
        return self.dds.guid.bytes

    def topic(self, name: str, typename: str) -> Topic:
        """The participant's topic of this name, made once, with the opaque type of typename."""
        if name not in self._topics:
            self._topics[name] = Topic(self.dds, name, opaque_type(typename))
        return self._topics[name]

    def writer(self, name: str, typename: str, qos: Qos, partition: str | None = None) -> DataWriter:
        """A new writer on the topic, in partition if given (else the default partition)."""
        publisher = Publisher(self.dds, qos=Qos(Policy.Partition([partition]))) if partition else self.dds
        return DataWriter(publisher, self.topic(name, typename), qos=qos)

    def reader(self, name: str, typename: str, qos: Qos, partition: str | None = None) -> DataReader:
        """A new reader of the topic, in partition if given (else the default partition)."""
        subscriber = Subscriber(self.dds, qos=Qos(Policy.Partition([partition]))) if partition else self.dds
        return DataReader(subscriber, self.topic(name, typename), qos=qos)


def take(reader: DataReader, limit: int = 256) -> Iterator[RawSample]:
    """The reader's new samples (up to limit) as bytes, none deserialized.

    A typed read would drop or choke on a sample in the other layout.
    """
    result: Any = ddspy_take(reader._ref, ANY_SAMPLE, limit)
    if isinstance(result, int):
        return
    for data, info in result:
        yield RawSample(bytes(data), bool(info.valid_data))


def write(writer: DataWriter, data: bytes) -> None:
    """Write an already serialized sample (encapsulation header included)."""
    result = ddspy_write(writer._ref, data)
    if isinstance(result, int) and result < 0:
        raise OSError(f'DDS write failed ({result})')


def entity_gid(entity: DataReader | DataWriter) -> bytes:
    """The reader's or writer's GUID (16 bytes), the gid a graph message lists it by."""
    return entity.guid.bytes
