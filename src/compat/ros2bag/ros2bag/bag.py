"""A bag as rosbag2 lays it out: a folder with `metadata.yaml` and `<folder>_0.mcap`.

BagWriter writes what `ros2 bag record` receives (serialized CDR messages, one MCAP channel per
topic, with the `ros2msg` schema of its type) and the metadata at the end; read_metadata and
messages() read a bag back. MCAP is the MCAP project's own Python library (`mcap` on PyPI).
"""

from __future__ import annotations

import datetime
import os
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from mcap.reader import make_reader
from mcap.writer import CompressionType, Writer

METADATA_FILE = 'metadata.yaml'
METADATA_VERSION = 9  # what Jazzy's rosbag2 writes
STORAGE_ID = 'mcap'
PROFILE = 'ros2'
SCHEMA_ENCODING = 'ros2msg'
MESSAGE_ENCODING = 'cdr'


class BagError(Exception):
    """A bag that cannot be written or read, said in one line."""


def default_bag_name(now: datetime.datetime | None = None) -> str:
    """rosbag2's default folder name: rosbag2_YYYY_MM_DD-HH_MM_SS (local time)."""
    return (now or datetime.datetime.now()).strftime('rosbag2_%Y_%m_%d-%H_%M_%S')


def duration_yaml(nanoseconds: int) -> dict[str, int]:
    """A QoS duration as rosbag2's metadata writes it."""
    return {'sec': nanoseconds // 10**9, 'nsec': nanoseconds % 10**9}


@dataclass
class TopicInfo:
    """One recorded topic: what its channel and the metadata say of it."""

    name: str
    type: str
    offered_qos_profiles: list[dict[str, Any]] = field(default_factory=list)
    type_description_hash: str = ''
    message_count: int = 0
    channel_id: int = 0


class BagWriter:
    """Writes one bag folder; close() finishes the MCAP file and writes metadata.yaml."""

    def __init__(self, folder: Path) -> None:
        if folder.exists():
            raise BagError(f"Output folder '{folder}' already exists.")
        try:
            folder.mkdir(parents=True)
        except OSError as error:
            raise BagError(f"Cannot create output folder '{folder}': {error.strerror}") from None
        self.folder = folder
        self.file_name = f'{folder.name}_0.mcap'
        self._stream = open(folder / self.file_name, 'wb')  # closed in close()
        self._writer = Writer(self._stream, compression=CompressionType.ZSTD)
        self._writer.start(profile=PROFILE, library='owl-kit-lab ros2bag')
        self.topics: dict[str, TopicInfo] = {}
        self._schemas: dict[str, int] = {}
        self.first_time: int | None = None
        self.last_time: int | None = None
        self.message_count = 0

    def add_topic(self, name: str, type_name: str, definition: str, qos_profiles: list[dict[str, Any]],
                  type_hash: str) -> None:
        """A channel for the topic (its type's schema registered once)."""
        if type_name not in self._schemas:
            self._schemas[type_name] = self._writer.register_schema(type_name, SCHEMA_ENCODING,
                                                                    definition.encode())
        info = TopicInfo(name, type_name, qos_profiles, type_hash)
        info.channel_id = self._writer.register_channel(
            name, MESSAGE_ENCODING, self._schemas[type_name],
            {'offered_qos_profiles': yaml.safe_dump(qos_profiles, sort_keys=False),
             'topic_type_hash': type_hash})
        self.topics[name] = info

    def write(self, topic: str, data: bytes, received_ns: int, sent_ns: int | None = None) -> None:
        """One serialized message of a topic added with add_topic."""
        info = self.topics[topic]
        info.message_count += 1
        self._writer.add_message(info.channel_id, log_time=received_ns, data=data,
                                 publish_time=sent_ns or received_ns, sequence=info.message_count)
        self.message_count += 1
        if self.first_time is None:
            self.first_time = received_ns
        self.last_time = received_ns

    def close(self) -> None:
        """Finish the MCAP file (its summary and index) and write metadata.yaml."""
        self._writer.finish()
        self._stream.close()
        (self.folder / METADATA_FILE).write_text(yaml.safe_dump(self.metadata(), sort_keys=False))

    def metadata(self) -> dict[str, Any]:
        """metadata.yaml's content, in the order and shape Jazzy's rosbag2 writes."""
        start = self.first_time or 0
        duration = (self.last_time or 0) - start
        return {'rosbag2_bagfile_information': {
            'version': METADATA_VERSION,
            'storage_identifier': STORAGE_ID,
            'duration': {'nanoseconds': duration},
            'starting_time': {'nanoseconds_since_epoch': start},
            'message_count': self.message_count,
            'topics_with_message_count': [
                {'topic_metadata': {'name': t.name, 'type': t.type, 'serialization_format': MESSAGE_ENCODING,
                                    'offered_qos_profiles': t.offered_qos_profiles,
                                    'type_description_hash': t.type_description_hash},
                 'message_count': t.message_count}
                for t in self.topics.values()],
            'compression_format': '',
            'compression_mode': '',
            'relative_file_paths': [self.file_name],
            'files': [{'path': self.file_name, 'starting_time': {'nanoseconds_since_epoch': start},
                       'duration': {'nanoseconds': duration}, 'message_count': self.message_count}],
            'custom_data': None,
            'ros_distro': os.environ.get('ROS_DISTRO', 'jazzy'),
        }}


def read_metadata(folder: Path) -> dict[str, Any]:
    """The bag's rosbag2_bagfile_information; BagError when the folder holds no readable bag."""
    path = folder / METADATA_FILE
    if not folder.is_dir():
        raise BagError(f"No bag at '{folder}': not a folder")
    try:
        data = yaml.safe_load(path.read_text())
        info = data['rosbag2_bagfile_information']
    except FileNotFoundError:
        raise BagError(f"No bag at '{folder}': it has no {METADATA_FILE}") from None
    except yaml.YAMLError as error:
        mark = getattr(error, 'problem_mark', None)
        where = f' at line {mark.line + 1}' if mark is not None else ''
        problem = getattr(error, 'problem', 'bad YAML')
        raise BagError(f"'{path}' is not rosbag2 metadata: {problem}{where}") from None
    except (TypeError, KeyError):
        raise BagError(f"'{path}' is not rosbag2 metadata: it has no rosbag2_bagfile_information") from None
    if info.get('storage_identifier') != STORAGE_ID:
        raise BagError(f"'{folder}' is stored as '{info.get('storage_identifier')}'; only mcap bags "
                       'can be read here')
    return info


@dataclass
class BagMessage:
    """One recorded message: its topic, type, receive time (ns) and CDR bytes."""

    topic: str
    type: str
    log_time: int
    data: bytes


def messages(folder: Path, topics: set[str] | None = None) -> Iterator[BagMessage]:
    """The bag's messages in receive-time order, all or those of the given topics."""
    info = read_metadata(folder)
    for relative in info.get('relative_file_paths', []):
        with open(folder / relative, 'rb') as stream:
            reader = make_reader(stream)
            try:
                for schema, channel, message in reader.iter_messages(
                        topics=sorted(topics) if topics is not None else None, log_time_order=True):
                    yield BagMessage(channel.topic, schema.name if schema else '', message.log_time,
                                     message.data)
            except Exception as error:  # a truncated or foreign file: say which, in one line
                raise BagError(f"'{folder / relative}' cannot be read: {error}") from None
