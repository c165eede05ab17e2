"""The topic inspector's rate, message summary and endpoints, without a node."""

import math

import pytest
from rqt_web.topic_inspector import SHOWN_CHARACTERS, ArrivalRate, endpoint_summary, message_summary
from sensor_msgs.msg import Image, Imu
from std_msgs.msg import String
from turtlesim.msg import Pose


def test_the_rate_is_measured_over_the_window_and_goes_when_the_topic_is_quiet():
    rate = ArrivalRate(window=5.0)
    assert rate.rate(0.0) is None
    for tick in range(51):  # 10 a second for 5 s
        rate.add(tick * 0.1)
    assert rate.rate(5.0) == pytest.approx(10.0)
    assert rate.rate(6.1) is not None  # a second and two periods: not yet quiet
    assert rate.rate(6.3) is None
    rate.add(20.0)
    assert rate.rate(20.0) is None  # one message in the window says no rate


def test_a_message_is_plain_data_with_long_sequences_and_strings_cut_before_any_conversion():
    pose = message_summary(Pose(x=1.5, theta=math.nan))
    assert pose == {'x': 1.5, 'y': 0.0, 'theta': 'nan', 'linear_velocity': 0.0, 'angular_velocity': 0.0}
    image = Image(height=480, width=640, encoding='rgb8', step=1920, data=bytes(640 * 480 * 3))
    summary = message_summary(image, shown_items=4)
    assert summary['data'] == [0, 0, 0, 0, '... (921596 more)']
    assert summary['header'] == {'stamp': {'sec': 0, 'nanosec': 0}, 'frame_id': ''}
    imu = message_summary(Imu())
    assert imu['orientation_covariance'] == [0.0] * 9  # a fixed-size array (numpy), as numbers
    text = message_summary(String(data='x' * (SHOWN_CHARACTERS + 5)))['data']
    assert text.endswith('... (5 more characters)')


def test_an_endpoint_is_its_node_and_qos():
    endpoint = {'node_name': 'turtlesim', 'node_namespace': '/', 'reliability': 'RELIABLE',
                'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC', 'history': 'UNKNOWN', 'depth': 0}
    assert endpoint_summary(endpoint) == {'node': '/turtlesim', 'reliability': 'RELIABLE',
                                          'durability': 'VOLATILE', 'liveliness': 'AUTOMATIC'}
    assert endpoint_summary({**endpoint, 'node_namespace': '/kit'})['node'] == '/kit/turtlesim'
