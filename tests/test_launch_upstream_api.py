"""An upstream-style launch file runs under `ros2 launch` over real DDS.

It has OnProcessExit imported from its upstream module path, a LifecycleNode that launch configures
and activates through the node's real lifecycle services, and `$(param ...)` reading what
SetParameter gave every node.
"""

import sys
import textwrap

from lifecycle_msgs.msg import State
from lifecycle_msgs.srv import GetState
from ros_harness import LAUNCH_STOP_TIMEOUT

# A lifecycle node as a student would write it with rclpy.lifecycle; it says which transitions ran.
LIFECYCLE_NODE = '''
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn


class Greeter(LifecycleNode):
    def __init__(self):
        super().__init__('greeter')
        self.declare_parameter('greeting', 'unset')

    def on_configure(self, state):
        self.get_logger().info('configured with greeting ' + self.get_parameter('greeting').value)
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        self.get_logger().info('activated')
        return TransitionCallbackReturn.SUCCESS


def main():
    rclpy.init()
    node = Greeter()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


main()
'''

LAUNCH_FILE = '''
import lifecycle_msgs.msg
from launch import LaunchDescription
from launch.actions import EmitEvent, ExecuteProcess, LogInfo, RegisterEventHandler
from launch.event_handlers.on_process_exit import OnProcessExit
from launch.events import matches_action
from launch_ros.actions import LifecycleNode, SetParameter
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState
from launch_ros.substitutions import Parameter


def generate_launch_description():
    greeter = LifecycleNode(executable=PYTHON, arguments=[SCRIPT], name='greeter', namespace='lab',
                            output='screen')
    echo = ExecuteProcess(cmd=['echo', 'param says', Parameter('greeting')], output='screen')
    return LaunchDescription([
        SetParameter('greeting', 'hello_from_launch'),
        greeter,
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=greeter, goal_state='inactive',
            entities=[EmitEvent(event=ChangeState(
                lifecycle_node_matcher=matches_action(greeter),
                transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE))])),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=greeter, goal_state='active', entities=[echo])),
        RegisterEventHandler(OnProcessExit(
            target_action=echo, on_exit=[LogInfo(msg='echo exited, greeter is active')])),
        EmitEvent(event=ChangeState(
            lifecycle_node_matcher=matches_action(greeter),
            transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE)),
    ])
'''


def launch_node_script(ros, tmp_path, node_source: str, launch_source: str):
    """`ros2 launch` of launch_source, whose PYTHON and SCRIPT name this Python and node_source's file."""
    script = tmp_path / 'node.py'
    script.write_text(node_source)
    launch_file = tmp_path / 'node_launch.py'
    launch_file.write_text(textwrap.dedent(launch_source).replace('PYTHON', repr(sys.executable))
                           .replace('SCRIPT', repr(str(script))))
    return ros.command(['ros2', 'launch', str(launch_file)])


def test_upstream_style_launch_file_drives_a_lifecycle_node_and_reads_a_param(ros, tmp_path):
    process = launch_node_script(ros, tmp_path, LIFECYCLE_NODE, LAUNCH_FILE)
    process.wait_for(r'\[lab\.greeter\]: configured with greeting hello_from_launch', timeout=60)
    process.wait_for(r'\[lab\.greeter\]: activated', timeout=30)
    process.wait_for(r'\[echo-\d+\] param says hello_from_launch', timeout=30)
    process.wait_for(r'\[INFO\] \[launch\.user\]: echo exited, greeter is active', timeout=30)
    state = ros.probe.call(GetState, '/lab/greeter/get_state', GetState.Request(), timeout=30,
                           resend_every=2.0).current_state
    assert (state.id, state.label) == (State.PRIMARY_STATE_ACTIVE, 'active')
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)


# A lifecycle node whose change_state service is found before its transition_event publisher: it
# announces a transition only once, as every lifecycle node does, and says whether anyone could hear.
LATE_ANNOUNCER = '''
import rclpy
from lifecycle_msgs.msg import State, TransitionEvent
from lifecycle_msgs.srv import ChangeState

rclpy.init()
node = rclpy.create_node('late', namespace='lab')
announcer = []


def change_state(request, response):
    heard = bool(announcer) and announcer[0].get_subscription_count() > 0
    if announcer:
        announcer[0].publish(TransitionEvent(
            transition=request.transition,
            start_state=State(id=State.TRANSITION_STATE_CONFIGURING, label='configuring'),
            goal_state=State(id=State.PRIMARY_STATE_INACTIVE, label='inactive')))
    node.get_logger().info('change_state ' + ('announced' if heard else 'unheard'))
    response.success = True
    return response


def announce_from_now():
    timer.cancel()
    announcer.append(node.create_publisher(TransitionEvent, '~/transition_event', 10))


node.create_service(ChangeState, '~/change_state', change_state)
timer = node.create_timer(1.5, announce_from_now)
try:
    rclpy.spin(node)
except KeyboardInterrupt:
    pass
finally:
    node.destroy_node()
    rclpy.try_shutdown()
'''

LATE_LAUNCH_FILE = '''
import lifecycle_msgs.msg
from launch import LaunchDescription
from launch.actions import EmitEvent, LogInfo, RegisterEventHandler
from launch.events import matches_action
from launch_ros.actions import LifecycleNode
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState


def generate_launch_description():
    late = LifecycleNode(executable=PYTHON, arguments=[SCRIPT], name='late', namespace='lab',
                         output='screen')
    return LaunchDescription([
        late,
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=late, goal_state='inactive',
            entities=[LogInfo(msg='launch saw the node become inactive')])),
        EmitEvent(event=ChangeState(lifecycle_node_matcher=matches_action(late),
                                    transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE)),
    ])
'''


def test_launch_changes_a_state_only_once_it_can_hear_the_transition(ros, tmp_path):
    process = launch_node_script(ros, tmp_path, LATE_ANNOUNCER, LATE_LAUNCH_FILE)
    process.wait_for(r'\[lab\.late\]: change_state (announced|unheard)', timeout=60)
    assert 'change_state announced' in process.output, process.output
    process.wait_for(r'\[INFO\] \[launch\.user\]: launch saw the node become inactive', timeout=15)
    process.stop_cleanly(timeout=LAUNCH_STOP_TIMEOUT)
