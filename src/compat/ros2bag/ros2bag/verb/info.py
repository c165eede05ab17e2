"""`ros2 bag info <bag>`: what a bag holds, from its metadata.yaml, as Jazzy prints it."""

from __future__ import annotations

import argparse
import datetime
from pathlib import Path
from typing import Any

from ros2cli.verb import VerbExtension

LABEL_WIDTH = 19  # 'Topic information: ' and every other label are padded to this
EVENT_SUFFIX = '/_service_event'


def size_text(size: float) -> str:
    """Bytes as rosbag2 prints a bag's size: 'B', then 'KiB', 'MiB', ... with one decimal."""
    units = ['B', 'KiB', 'MiB', 'GiB', 'TiB']
    unit = 0
    while size >= 1024 and unit < len(units) - 1:
        size /= 1024
        unit += 1
    return f'{int(size)} B' if unit == 0 else f'{size:.1f} {units[unit]}'


def time_text(nanoseconds: int) -> str:
    """'Nov 28 2026 07:55:54.123456789 (1795852554.123456789)', in local time (the day space-padded)."""
    seconds, fraction = divmod(nanoseconds, 10**9)
    when = datetime.datetime.fromtimestamp(seconds)
    return f"{when.strftime('%b %e %Y %H:%M:%S')}.{fraction:09d} ({seconds}.{fraction:09d})"


def duration_text(nanoseconds: int) -> str:
    """'12.345678901s'."""
    seconds, fraction = divmod(nanoseconds, 10**9)
    return f'{seconds}.{fraction:09d}s'


def info_lines(folder: Path, info: dict[str, Any]) -> list[str]:
    """The lines `ros2 bag info` prints for a bag's metadata."""
    files = info.get('relative_file_paths', [])
    size = sum(path.stat().st_size for path in folder.iterdir() if path.is_file())  # metadata.yaml too
    start = info['starting_time']['nanoseconds_since_epoch']
    duration = info['duration']['nanoseconds']
    topics = info.get('topics_with_message_count', [])
    plain = [t for t in topics if not t['topic_metadata']['name'].endswith(EVENT_SUFFIX)]
    services = [t for t in topics if t['topic_metadata']['name'].endswith(EVENT_SUFFIX)]

    def label(name: str) -> str:
        return f'{name}:'.ljust(LABEL_WIDTH)

    lines = [label('Files') + (files[0] if files else '')]
    lines += [' ' * LABEL_WIDTH + name for name in files[1:]]
    lines += [label('Bag size') + size_text(size), label('Storage id') + info['storage_identifier'],
              label('ROS Distro') + str(info.get('ros_distro', 'unknown')),
              label('Duration') + duration_text(duration),
              label('Start') + time_text(start), label('End') + time_text(start + duration),
              # Messages of topics; the services' events are counted below.
              label('Messages') + str(info['message_count'] - sum(t['message_count'] for t in services))]
    entries = [f"Topic: {t['topic_metadata']['name']} | Type: {t['topic_metadata']['type']} | Count: "
               f"{t['message_count']} | Serialization Format: {t['topic_metadata']['serialization_format']}"
               for t in plain]
    lines.append(label('Topic information') + (entries[0] if entries else ''))
    lines += [' ' * LABEL_WIDTH + entry for entry in entries[1:]]
    lines.append(label('Service') + str(len(services)))
    entries = [f"Service: {t['topic_metadata']['name'].removesuffix(EVENT_SUFFIX)} | Type: "
               f"{t['topic_metadata']['type'].removesuffix('_Event')} | Event Count: {t['message_count']} | "
               f"Serialization Format: {t['topic_metadata']['serialization_format']}" for t in services]
    # Unlike the topics', the services' lines are indented by their whole label (as upstream).
    lines.append('Service information: ' + (entries[0] if entries else ''))
    lines += [' ' * len('Service information: ') + entry for entry in entries[1:]]
    return lines


class InfoVerb(VerbExtension):
    """Print information about a bag to the screen."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """The bag's folder; -s/--storage is accepted (mcap only)."""
        parser.add_argument('bag_path', help='Bag to open')
        parser.add_argument('-s', '--storage', default='mcap',
                            help="Storage implementation of bag (only 'mcap').")

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the bag's summary; a folder that is no bag is a one-line error."""
        from ros2bag.bag import BagError, read_metadata

        folder = Path(args.bag_path)
        try:
            info = read_metadata(folder)
            lines = info_lines(folder, info)
        except BagError as error:
            return str(error)
        except (KeyError, TypeError) as error:
            return f"'{folder / 'metadata.yaml'}' misses {error}: it is not rosbag2 metadata"
        print()
        print('\n'.join(lines))
        print()
        return 0
