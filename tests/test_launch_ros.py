"""`ros2 launch` of ROS nodes over real DDS: the course's turtlesim launch files and a Node's settings.

The course's turtlesim launch files (section 3.9), and a Node's name, namespace, parameters and
remappings as the running node sees them.
"""

import os
import re
import signal
import subprocess
import textwrap
import time
from pathlib import Path

import pytest
from owl_common.processes import dies_with_this_process
from ros_harness import LAUNCH_STOP_TIMEOUT, wait_until
from std_msgs.msg import Int32

STARTED = r'\[INFO\] \[([\w.-]+)\]: process started with pid \[(\d+)\]'
COURSE_LAUNCH_DIR = Path(__file__).resolve().parents[1] / 'src' / 'course' / 'olive_launch' / 'launch'
# The promise: Ctrl-C brings everything down within 5 s (launch's own SIGTERM escalation
# would only start after 5 s).  A little slack for a loaded machine.
CTRL_C_LIMIT = 6.0


def alive(pid: int) -> bool:
    try:
        with open(f'/proc/{pid}/stat') as handle:
            return handle.read().split(')')[-1].split()[0] != 'Z'
    except FileNotFoundError:
        return False


def child_pids_of(output: str) -> list[int]:
    return [int(pid) for _label, pid in re.findall(STARTED, output)]


def child_pids(process) -> list[int]:
    return child_pids_of(process.output)


def test_course_launch_file_verbatim_starts_two_turtles_and_sigint_stops_them(ros):
    # As in the course: `ros2 launch turtle.launch.py` inside the package's launch directory.
    process = ros.command(['ros2', 'launch', 'turtle.launch.py'], cwd=str(COURSE_LAUNCH_DIR))
    process.wait_for(STARTED, timeout=30, count=2)
    ros.probe.wait_for_node('turtle1', timeout=30)
    ros.probe.wait_for_node('turtle2', timeout=30)
    pids = child_pids(process)
    assert len(pids) == 2
    process.wait_for(r'\[turtlesim_node-\d+\] .*\[turtle1\]')
    process.wait_for(r'\[turtlesim_node-\d+\] .*\[turtle2\]')
    started = time.monotonic()
    # SIGINT to launch alone (a script, or `kill -INT`): launch forwards it to each node once.
    os.kill(process.pid, signal.SIGINT)
    assert process.wait(30) == 0, process.output
    elapsed = time.monotonic() - started
    assert elapsed < CTRL_C_LIMIT, f'took {elapsed:.1f} s\n{process.output}'
    process.wait_for(r'\[WARNING\] \[launch\]: user interrupted with ctrl-c \(SIGINT\)')
    process.wait_for(r"\[INFO\] \[turtlesim_node-\d+\]: sending signal 'SIGINT'", count=2)
    process.wait_for(r'\[INFO\] \[turtlesim_node-\d+\]: process has finished cleanly \[pid \d+\]', count=2)
    assert not [pid for pid in pids if alive(pid)]


def test_ctrl_c_in_a_terminal_stops_the_package_launch_file(ros, tmp_path):
    """`ros2 launch olive_launch turtle_launch.py` in a terminal, then Ctrl-C: all down within 5 s.

    The terminal signals launch and both nodes; launch does not repeat the SIGINT and everything is down
    within 5 s.
    """
    terminal, terminal_side = os.openpty()
    log = tmp_path / 'terminal.log'
    with open(log, 'w') as out:
        launch = subprocess.Popen(['ros2', 'launch', 'olive_launch', 'turtle_launch.py'],
                                  stdin=terminal_side, stdout=out, stderr=subprocess.STDOUT, env=ros.env,
                                  start_new_session=True, preexec_fn=dies_with_this_process())
    os.close(terminal_side)
    try:
        ros.probe.wait_for_node('turtle1', timeout=30)
        ros.probe.wait_for_node('turtle2', timeout=30)
        started = time.monotonic()
        os.killpg(launch.pid, signal.SIGINT)  # what Ctrl-C in the terminal does
        assert launch.wait(30) == 0
        elapsed = time.monotonic() - started
    finally:
        os.close(terminal)
        if launch.poll() is None:
            os.killpg(launch.pid, signal.SIGKILL)
    output = log.read_text()
    assert elapsed < CTRL_C_LIMIT, f'took {elapsed:.1f} s\n{output}'
    assert '[WARNING] [launch]: user interrupted with ctrl-c (SIGINT)' in output
    assert "sending signal 'SIGINT'" not in output
    finished = re.findall(r'\[INFO\] \[turtlesim_node-\d+\]: process has finished cleanly', output)
    assert len(finished) == 2, output
    assert not [pid for pid in child_pids_of(output) if alive(pid)]


@pytest.mark.parametrize('launch_file', ['turtle_launch.py', 'turtle_launch.xml', 'turtle_launch.yaml'])
def test_olive_launch_package_files_bring_up_turtle1_and_turtle2(ros, launch_file):
    process = ros.command(['ros2', 'launch', 'olive_launch', launch_file])
    ros.probe.wait_for_node('turtle1', timeout=30)
    ros.probe.wait_for_node('turtle2', timeout=30)
    labels = sorted(label for label, _pid in re.findall(STARTED, process.output))
    assert [re.sub(r'-\d+$', '', label) for label in labels] == ['turtlesim_node'] * 2
    pids = child_pids(process)
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)
    assert not [pid for pid in pids if alive(pid)]


PARAMS_FILE = '/**:\n  ros__parameters:\n    lower_limit: 7\n'
NODE_FILES = {
    'py': ('numbers_launch.py', '''
        from launch import LaunchDescription
        from launch.actions import DeclareLaunchArgument, GroupAction
        from launch.substitutions import LaunchConfiguration
        from launch_ros.actions import Node, PushRosNamespace

        def generate_launch_description():
            return LaunchDescription([
                DeclareLaunchArgument('limit', default_value='100'),
                GroupAction([
                    PushRosNamespace('lab'),
                    Node(package='random_number_ps', executable='random_number_publisher', name='pub',
                         parameters=['PARAMS', {'upper_limit': LaunchConfiguration('limit')}],
                         remappings=[('random_numbers', 'numbers')], output='screen'),
                ]),
            ])
        '''),
    'xml': ('numbers.launch.xml', '''
        <launch>
          <arg name="limit" default="100"/>
          <group>
            <push_ros_namespace namespace="lab"/>
            <node pkg="random_number_ps" exec="random_number_publisher" name="pub" output="screen">
              <param from="PARAMS"/>
              <param name="upper_limit" value="$(var limit)"/>
              <remap from="random_numbers" to="numbers"/>
            </node>
          </group>
        </launch>
        '''),
    'yaml': ('numbers.launch.yaml', '''
        launch:
        - arg: {name: limit, default: '100'}
        - group:
            children:
            - push_ros_namespace: {namespace: lab}
            - node:
                pkg: random_number_ps
                exec: random_number_publisher
                name: pub
                output: screen
                param:
                - {from: PARAMS}
                - {name: upper_limit, value: $(var limit)}
                remap:
                - {from: random_numbers, to: numbers}
        '''),
}


@pytest.mark.parametrize('fmt', NODE_FILES)
def test_node_name_namespace_parameters_and_remapping_reach_the_node(ros, tmp_path, fmt):
    params = tmp_path / 'params.yaml'
    params.write_text(PARAMS_FILE)
    name, text = NODE_FILES[fmt]
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip().replace('PARAMS', str(params)))
    received = ros.probe.collect(Int32, '/lab/numbers')
    process = ros.command(['ros2', 'launch', str(path), 'limit:=7'])
    process.wait_for(r'\[lab\.pub\]: Publishing: 7', timeout=30)
    wait_until(lambda: len(received) >= 2, 30, 'two numbers on /lab/numbers')
    assert {message.data for message in received} == {7}
    assert ros.probe.get_parameters('/lab/pub', 'lower_limit', 'upper_limit') == [7, 7]
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)
