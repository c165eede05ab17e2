"""ros2doctor's plain parts: report layout, distribution support, pins; no ROS graph."""

import datetime

from ros2doctor.api import Report
from ros2doctor.api.format import format_report
from ros2doctor.api.package import package_of_wheel, ros_pins
from ros2doctor.api.platform import distribution_status


def report(*items):
    made = Report('TOPIC LIST')
    for key, value in items:
        made.add_to_report(key, value)
    return made


def test_keys_are_padded_to_the_longest_plus_four():
    text = format_report(report(('topic', '/chatter'), ('publisher count', 1), ('subscriber count', 0)))
    assert text.splitlines() == ['', '   TOPIC LIST', 'topic               : /chatter',
                                 'publisher count     : 1', 'subscriber count    : 0']


def test_short_keys_get_at_least_eight():
    assert format_report(report(('system', 'Linux'))).splitlines()[2] == 'system  : Linux'
    assert format_report(report()).splitlines() == ['', '   TOPIC LIST']


def test_distribution_support_by_date():
    assert distribution_status('jazzy', datetime.date(2026, 11, 28)) == 'active'
    assert distribution_status('humble', datetime.date(2027, 6, 1)) == 'end-of-life'
    assert distribution_status('iron', datetime.date(2026, 1, 1)) == 'end-of-life'
    assert distribution_status('rolling') == 'rolling'
    assert distribution_status('ardent-typo') is None


def test_pins_are_read_from_the_projects_requirements(tmp_path, monkeypatch):
    (tmp_path / 'requirements.txt').write_text(
        'ros-jazzy-rclpy==7.1.6\n    # via x\nros-jazzy-std-msgs==5.3.6 ; python_version >= "3.10"\n'
        'ros-ament-index-python==1.8.1\nnumpy==2.4.6\n')
    monkeypatch.setenv('OWL_ROOT', str(tmp_path))
    assert ros_pins() == {'ros-jazzy-rclpy': '7.1.6', 'ros-jazzy-std-msgs': '5.3.6',
                          'ros-ament-index-python': '1.8.1'}
    assert package_of_wheel('ros-jazzy-std-msgs') == 'std_msgs'
    assert package_of_wheel('ros-ament-index-python') == 'ament_index_python'
    monkeypatch.setenv('OWL_ROOT', str(tmp_path / 'missing'))
    assert ros_pins() == {}
