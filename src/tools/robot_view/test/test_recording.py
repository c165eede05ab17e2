"""The Record button's folder names, bag summary and command, without a node or a recorder."""

import datetime
from pathlib import Path

import pytest
import yaml
from owl_web.codec import ApiError
from robot_view.recording import (
    RECORDED_TOPICS,
    bag_summary,
    new_bag_folder,
    record_request,
    recordings_folder,
)

NOW = datetime.datetime(2026, 12, 3, 8, 30, 5)


def test_recordings_go_to_owl_recordings_unless_the_environment_says_elsewhere(tmp_path: Path):
    assert recordings_folder({}) == Path.home() / 'owl_recordings'
    assert recordings_folder({'OWL_RECORDINGS': str(tmp_path)}) == tmp_path


def test_a_new_recording_never_takes_an_existing_folder(tmp_path: Path):
    first = new_bag_folder(tmp_path, NOW)
    assert first == tmp_path / 'robot_view_2026_12_03-08_30_05'
    first.mkdir()
    assert new_bag_folder(tmp_path, NOW) == tmp_path / 'robot_view_2026_12_03-08_30_05_2'


def test_the_recorded_topics_are_the_plotted_ones():
    assert RECORDED_TOPICS == ('/olive/servo/pan/joint', '/olive/servo/pan/goal/position',
                               '/olive/servo/tilt/joint', '/olive/servo/tilt/goal/position',
                               '/olive/imu/x1684267976913/imu')


def test_a_bag_is_summed_up_from_its_metadata_and_a_broken_one_is_one_line(tmp_path: Path):
    metadata = {'rosbag2_bagfile_information': {
        'message_count': 3, 'duration': {'nanoseconds': 1_500_000_000},
        'topics_with_message_count': [{'topic_metadata': {'name': '/a'}, 'message_count': 2},
                                      {'topic_metadata': {'name': '/b'}, 'message_count': 1}]}}
    (tmp_path / 'metadata.yaml').write_text(yaml.safe_dump(metadata))
    assert bag_summary(tmp_path) == {'folder': str(tmp_path), 'messages': 3, 'seconds': 1.5,
                                     'topics': {'/a': 2, '/b': 1}}
    (tmp_path / 'metadata.yaml').write_text('rosbag2_bagfile_information: {}')
    with pytest.raises(ApiError, match=r'has no readable metadata\.yaml') as broken:
        bag_summary(tmp_path)
    assert '\n' not in broken.value.message


def test_the_record_command_takes_on_true_or_false():
    assert record_request({'on': True}) is True
    assert record_request({'on': False}) is False
    for arguments, error in (({}, "missing key 'on'"), ({'on': 1}, '"on" must be true or false, got 1'),
                             ({'on': True, 'folder': '/'}, "unknown key 'folder'; expected: on")):
        with pytest.raises(ApiError) as refused:
            record_request(arguments)
        assert refused.value.message == error
