"""ros2bag's plain parts without a ROS graph: schemas, the bag folder, info's text, types, play's rules."""

from pathlib import Path

import pytest
from example_interfaces.srv import AddTwoInts
from mcap_ros2.decoder import DecoderFactory
from rclpy.serialization import serialize_message
from ros2bag.bag import BagError, BagWriter, messages, read_metadata
from ros2bag.definitions import SEPARATOR, message_definition
from ros2bag.interfaces import import_type
from ros2bag.verb.info import duration_text, info_lines, size_text
from ros2bag.verb.play import writers_without_readers
from sensor_msgs.msg import Image


def test_a_schema_holds_every_nested_type_once():
    text = message_definition(Image)
    assert text.startswith('std_msgs/Header header\nuint32 height\n')
    assert 'uint8[] data\n' in text
    assert text.count(f'{SEPARATOR}\nMSG: std_msgs/Header\n') == 1
    assert text.count('MSG: builtin_interfaces/Time\n') == 1
    event = message_definition(AddTwoInts.Event)
    assert 'example_interfaces/AddTwoInts_Request[<=1] request\n' in event
    assert 'MSG: example_interfaces/AddTwoInts_Response\nint64 sum\n' in event


def test_written_messages_read_back_in_order_and_decode_with_the_mcap_library(tmp_path: Path):
    bag = tmp_path / 'images'
    writer = BagWriter(bag)
    writer.add_topic('/camera', 'sensor_msgs/msg/Image', message_definition(Image), [], 'RIHS01_x')
    for stamp in (30, 10, 20):
        writer.write('/camera', serialize_message(Image(height=stamp, encoding='mono8')), stamp)
    writer.close()
    info = read_metadata(bag)
    assert info['message_count'] == 3
    assert info['starting_time'] == {'nanoseconds_since_epoch': 30}
    read = list(messages(bag))
    assert [m.log_time for m in read] == [10, 20, 30]
    decode = DecoderFactory().decoder_for('cdr', _schema(bag))
    assert decode is not None
    assert [decode(m.data).height for m in read] == [10, 20, 30]
    lines = info_lines(bag, info)
    assert lines[0] == 'Files:             images_0.mcap'
    assert lines[-3].startswith('Topic information: Topic: /camera | Type: sensor_msgs/msg/Image | Count: 3')
    with pytest.raises(BagError, match=r"Output folder '.*images' already exists"):
        BagWriter(bag)


def _schema(bag: Path):
    from mcap.reader import make_reader
    with open(bag / 'images_0.mcap', 'rb') as stream:
        summary = make_reader(stream).get_summary()
    assert summary is not None
    return next(iter(summary.schemas.values()))


def test_sizes_and_durations_as_info_prints_them():
    assert size_text(512) == '512 B'
    assert size_text(1536) == '1.5 KiB'
    assert size_text(3 * 2**20) == '3.0 MiB'
    assert duration_text(12_345_678_901) == '12.345678901s'


@pytest.mark.parametrize(('name', 'reason'), [
    ('std_msgs/String', 'is not a type name'),
    ('no_such_pkg/msg/X', "no interface package 'no_such_pkg'"),
    ('std_msgs/msg/Nope', "'std_msgs' has no msg type 'Nope'"),
])
def test_type_names_that_do_not_resolve_say_why(name: str, reason: str):
    with pytest.raises(ValueError, match=reason):
        import_type(name)
    assert import_type('example_interfaces/srv/AddTwoInts_Event') is AddTwoInts.Event


def test_play_waits_for_a_participant_whose_writers_it_has_seen_but_no_reader():
    listener, player, daemon = b'listener', b'player', b'daemon'
    assert writers_without_readers([]) == set()
    # The listener's writers came first; its readers (rmw's ros_discovery_info one among them) later.
    seen = [(player, False), (player, True), (listener, False), (daemon, True), (daemon, False)]
    assert writers_without_readers(seen) == {listener}
    assert writers_without_readers([*seen, (listener, True)]) == set()
    assert writers_without_readers([(listener, True)]) == set()  # readers first: nothing to wait for
