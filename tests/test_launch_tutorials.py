"""Launch files shaped like the ROS 2 launch tutorials run unchanged through `ros2 launch`.

The tutorials' turtlesim mimic, substitutions and event handlers, with turtlesim over real DDS.
"""

import os
import re
import signal
import textwrap

from ros_harness import LAUNCH_STOP_TIMEOUT, wait_until

STARTED = r'\[INFO\] \[(.+?)\]: process started with pid \[(\d+)\]'

MIMIC = '''
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='turtlesim', namespace='turtlesim1', executable='turtlesim_node', name='sim'),
        Node(package='turtlesim', namespace='turtlesim2', executable='turtlesim_node', name='sim'),
        Node(package='turtlesim', executable='mimic', name='mimic', remappings=[
            ('/input/pose', '/turtlesim1/turtle1/pose'),
            ('/output/cmd_vel', '/turtlesim2/turtle1/cmd_vel'),
        ]),
    ])
'''

SUBSTITUTIONS = '''
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, TimerAction
from launch.conditions import IfCondition
from launch.substitutions import FindExecutable, LaunchConfiguration, PythonExpression
from launch_ros.actions import Node


def generate_launch_description():
    namespace = LaunchConfiguration('turtlesim_ns')
    use_red = LaunchConfiguration('use_provided_red')
    red = LaunchConfiguration('new_background_r')
    ros2 = FindExecutable(name='ros2')
    return LaunchDescription([
        DeclareLaunchArgument('turtlesim_ns', default_value='turtlesim1'),
        DeclareLaunchArgument('use_provided_red', default_value='False'),
        DeclareLaunchArgument('new_background_r', default_value='200'),
        Node(package='turtlesim', namespace=namespace, executable='turtlesim_node', name='sim'),
        ExecuteProcess(cmd=[[ros2, ' service call ', namespace, '/spawn turtlesim/srv/Spawn ',
                             '"{x: 2, y: 2, theta: 0.2}"']], shell=True),
        TimerAction(period=3.0, actions=[ExecuteProcess(
            condition=IfCondition(PythonExpression([red, ' == 200', ' and ', use_red])),
            cmd=[[ros2, ' param set ', namespace, '/sim background_r ', red]], shell=True)]),
    ])
'''

MAIN = '''
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution, ThisLaunchFileDir


def generate_launch_description():
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(
                PathJoinSubstitution([ThisLaunchFileDir(), 'example_substitutions_launch.py'])),
            launch_arguments={'turtlesim_ns': 'turtlesim2', 'use_provided_red': 'True',
                              'new_background_r': '200'}.items()),
    ])
'''

EVENT_HANDLERS = '''
from launch import LaunchDescription
from launch.actions import EmitEvent, ExecuteProcess, LogInfo, RegisterEventHandler
from launch.event_handlers import (OnExecutionComplete, OnProcessExit, OnProcessIO, OnProcessStart,
                                   OnShutdown)
from launch.events import Shutdown
from launch.substitutions import EnvironmentVariable, FindExecutable, LocalSubstitution
from launch_ros.actions import Node


def generate_launch_description():
    turtlesim = Node(package='turtlesim', namespace='turtlesim1', executable='turtlesim_node', name='sim')
    spawn = ExecuteProcess(cmd=[[FindExecutable(name='ros2'), ' service call /turtlesim1/spawn ',
                                 'turtlesim/srv/Spawn ', '"{x: 2, y: 2, theta: 0.2}"']], shell=True)
    return LaunchDescription([
        turtlesim,
        RegisterEventHandler(OnProcessStart(target_action=turtlesim, on_start=[
            LogInfo(msg='Turtlesim started, spawning turtle'), spawn])),
        RegisterEventHandler(OnProcessIO(target_action=spawn, on_stdout=lambda event: LogInfo(
            msg='Spawn request says "{}"'.format(event.text.decode().strip())))),
        RegisterEventHandler(OnExecutionComplete(target_action=spawn, on_completion=[
            LogInfo(msg='Spawn finished')])),
        RegisterEventHandler(OnProcessExit(target_action=turtlesim, on_exit=[
            LogInfo(msg=(EnvironmentVariable(name='USER'), ' closed the turtlesim window')),
            EmitEvent(event=Shutdown(reason='Window closed'))])),
        RegisterEventHandler(OnShutdown(on_shutdown=[
            LogInfo(msg=['Launch was asked to shutdown: ', LocalSubstitution('event.reason')])])),
    ])
'''


def write(directory, name, text):
    path = directory / name
    path.write_text(textwrap.dedent(text).lstrip())
    return str(path)


def test_mimic_tutorial_labels_and_graph(ros, tmp_path):
    process = ros.command(['ros2', 'launch', write(tmp_path, 'turtlesim_mimic_launch.py', MIMIC)])
    matches = process.wait_for(STARTED, timeout=30, count=3)
    labels = [re.sub(r'-\d+$', '', m.group(1)) for m in matches]
    assert labels == ['turtlesim_node', 'turtlesim_node', 'mimic']
    expected = {('sim', '/turtlesim1'), ('sim', '/turtlesim2'), ('mimic', '/')}
    wait_until(lambda: expected <= set(ros.probe.node.get_node_names_and_namespaces()), 30,
               'both simulators and mimic in the graph')
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)


def test_substitutions_tutorial_include_with_arguments(ros, tmp_path):
    write(tmp_path, 'example_substitutions_launch.py', SUBSTITUTIONS)
    process = ros.command(['ros2', 'launch', write(tmp_path, 'example_main_launch.py', MAIN)])
    # The spawn service call reached the namespaced simulator given by the include's argument.
    process.wait_for(r'\[turtlesim2\.sim\]: Spawning turtle \[turtle2\] at x=\[2\.0+\], y=\[2\.0+\]',
                     timeout=30)
    # The timer's conditional process ran, labelled (as upstream) by the basename of its command.
    process.wait_for(r'\[INFO\] \[sim background_r 200-\d+\]: process started with pid', timeout=40)
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)


def test_event_handlers_tutorial(ros, tmp_path):
    path = write(tmp_path, 'example_event_handlers_launch.py', EVENT_HANDLERS)
    process = ros.command(['ros2', 'launch', path], env={'USER': 'student'})
    for line in ('Turtlesim started, spawning turtle', 'Spawn request says "requester: making request:',
                 'Spawn finished'):
        process.wait_for(r'\[INFO\] \[launch\.user\]: ' + re.escape(line), timeout=40)
    # Closing the simulator ends the launch through OnProcessExit -> EmitEvent(Shutdown).
    started = re.search(r'\[turtlesim_node-\d+\]: process started with pid \[(\d+)\]', process.output)
    assert started, process.output
    turtlesim_pid = int(started.group(1))
    os.kill(turtlesim_pid, signal.SIGINT)
    assert process.wait(30) == 0, process.output
    process.wait_for(r'\[INFO\] \[launch\.user\]: student closed the turtlesim window')
    process.wait_for(r'\[INFO\] \[launch\.user\]: Launch was asked to shutdown: Window closed')
