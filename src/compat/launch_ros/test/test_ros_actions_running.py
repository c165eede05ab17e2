"""launch_ros actions inside a running LaunchService (no ROS graph needed: the nodes are `true`)."""

import pytest
from launch import LaunchDescription, LaunchService
from launch.actions import LogInfo
from launch_ros.actions import Node, PushRosNamespace, RosTimer


@pytest.fixture(autouse=True)
def log_dir(tmp_path, monkeypatch):
    monkeypatch.setenv('ROS_LOG_DIR', str(tmp_path))


def run(*entities) -> int:
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription(list(entities)))
    return service.run()


def test_duplicate_node_names_are_warned_about_on_the_process_label(capsys):
    assert run(Node(executable='true', name='twin', namespace='ns'),
               Node(executable='true', name='twin', exec_name='second', namespace='ns')) == 0
    out = capsys.readouterr().out
    assert '[WARNING] [second-' in out, out
    assert ('there are now at least 2 nodes with the name /ns/twin created '
            'within this launch context' in out), out
    assert "cmd 'true --ros-args" not in out  # both exited cleanly
    assert out.count('process has finished cleanly') == 2


def test_ros_timer_and_the_humble_spellings(capsys):
    assert run(PushRosNamespace('later'), RosTimer(period=0.2, actions=[LogInfo(msg='fired')])) == 0
    assert '[INFO] [launch.user]: fired' in capsys.readouterr().out
