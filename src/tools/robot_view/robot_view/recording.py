"""The robot view's Record button: the kit's servo and IMU topics in a bag, as `ros2 bag record` writes it.

The recording is `ros2 bag record` itself, run as a child process (on a normal ROS 2 install it is
rosbag2's), so the bag is one `ros2 bag info` and `ros2 bag play` read. The page keeps what it
plotted meanwhile, to draw it faintly under the live plots (plot_data.js).
"""

from __future__ import annotations

import contextlib
import datetime
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import yaml
from olive_kit.description import IMU_TOPIC, goal_topic, joint_topic
from owl_common.processes import RosProcess
from owl_web import codec
from owl_web.codec import ApiError

from robot_view.controls import SERVOS

# What the plots show: each servo's joint and goals, and the IMU (no camera: 30 images a second
# would make a minute's bag hundreds of megabytes).
RECORDED_TOPICS = (*(topic(servo) for servo in SERVOS for topic in (joint_topic, goal_topic)), IMU_TOPIC)
START_TIMEOUT = 15.0  # s for `ros2 bag record` to listen (its imports on a loaded machine)
# s more for it to have subscribed to every topic (a module that does not run never comes: the
# recording goes on without it, and takes it when it starts)
SUBSCRIBED_TIMEOUT = 5.0
STOP_TIMEOUT = 10.0  # s for it to finish the bag after Ctrl-C


def recordings_folder(environ: Mapping[str, str] = os.environ) -> Path:
    """Where recordings go: $OWL_RECORDINGS, else ~/owl_recordings."""
    return Path(environ.get('OWL_RECORDINGS') or Path.home() / 'owl_recordings')


def new_bag_folder(base: Path, now: datetime.datetime) -> Path:
    """A folder name for a recording that starts now, not taken yet (rosbag2 refuses an existing one)."""
    stem = now.strftime('robot_view_%Y_%m_%d-%H_%M_%S')
    folder, number = base / stem, 1
    while folder.exists():
        number += 1
        folder = base / f'{stem}_{number}'
    return folder


def bag_summary(folder: Path) -> dict[str, Any]:
    """What a finished bag holds, from its metadata.yaml: folder, messages, seconds, per-topic counts."""
    try:
        info = yaml.safe_load((folder / 'metadata.yaml').read_text())['rosbag2_bagfile_information']
        topics = {entry['topic_metadata']['name']: entry['message_count']
                  for entry in info['topics_with_message_count']}
        return {'folder': str(folder), 'messages': info['message_count'],
                'seconds': round(info['duration']['nanoseconds'] / 1e9, 3), 'topics': topics}
    except (OSError, yaml.YAMLError, KeyError, TypeError) as error:
        raise ApiError(500, f'the recording in {folder} has no readable metadata.yaml: {error}') from None


class BagRecording:
    """One running `ros2 bag record` of RECORDED_TOPICS into a new folder under base."""

    def __init__(self, base: Path, now: datetime.datetime) -> None:
        try:
            base.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            raise ApiError(500, f'cannot make the recordings folder {base}: {error.strerror}') from None
        self.folder = new_bag_folder(base, now)
        self.process = RosProcess(['ros2', 'bag', 'record', '-o', str(self.folder), *RECORDED_TOPICS],
                                  env=dict(os.environ), label='ros2 bag record')
        try:
            self.process.wait_for(r'Listening for topics', START_TIMEOUT)
        except AssertionError:
            self.process.stop(STOP_TIMEOUT)
            raise ApiError(500, f"ros2 bag record did not start within {START_TIMEOUT:g} s: "
                                f"{self.process.tail(1)}") from None
        with contextlib.suppress(AssertionError):  # the recording starts when all is subscribed
            self.process.wait_for(r'All requested topics are subscribed', SUBSCRIBED_TIMEOUT)

    def stop(self) -> dict[str, Any]:
        """Ctrl-C for `ros2 bag record`, which finishes the bag; what the bag holds."""
        code = self.process.stop(STOP_TIMEOUT)
        if code != 0:
            raise ApiError(500, f'ros2 bag record ended with exit code {code}: {self.process.tail(1)}')
        return bag_summary(self.folder)


def record_request(arguments: dict[str, Any]) -> bool:
    """A page's "record" command ({"on": true} starts a recording, {"on": false} stops it)."""
    codec.check_keys(arguments, ('on',), required=('on',))
    return codec.boolean(arguments['on'], '"on"')
