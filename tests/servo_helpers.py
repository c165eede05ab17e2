"""Helpers of the system tests that drive olive_sim's servos.

They start a kit servo, watch its topics, and check that it never saw a goal before its torque was
on nor one outside its bounds.
"""

from typing import Any

from diagnostic_msgs.msg import DiagnosticStatus
from olive_kit.description import OWL_KIT
from ros_harness import RosHarness
from sensor_msgs.msg import JointState
from std_msgs.msg import Float32

# The kit's servos as owl_kit.launch.py starts them (bounds, the camera's load on tilt).
SERVO_PARAMETERS = {m.namespace: m.parameters for m in OWL_KIT if m.module_type == 'servo'}
BOUNDS = {name: (p['min_position'], p['max_position']) for name, p in SERVO_PARAMETERS.items()}
TORQUE_OFF_WARNING = 'ignored, torque is disabled'
CLAMP_WARNING = 'clamped'


def start_servo(ros: RosHarness, name: str) -> Any:
    """olive_sim's servo_sim with the kit's parameters of the pan or tilt servo, without its web page.

    The tests that use it drive the servo over ROS; the page (tests/test_olive_module_pages.py) costs
    a quarter of the servo's start-up CPU.
    """
    args = [arg for key, value in SERVO_PARAMETERS[name].items() for arg in ('-p', f'{key}:={value}')]
    return ros.run('olive_sim', 'servo_sim', '--ros-args', *args, '-p', 'web_port:=0',
                   label=f'servo_sim {name}')


COLLECT_DEPTH = 1000


def collect(ros: RosHarness, name: str, topic: str) -> list[Any]:
    """Every message from now on of a servo's goal/position, joint or joint/diagnostics topic."""
    msg_type = {'goal/position': Float32, 'joint': JointState, 'joint/diagnostics': DiagnosticStatus}[topic]
    # A deep history: DDS keeps receiving while a busy machine holds the probe's Python back; with
    # the default 10, a stall of 0.1 s at 100 Hz lost messages (a test missed 57+ goals in a row).
    return ros.probe.collect(msg_type, f'/olive/servo/{name}/{topic}', COLLECT_DEPTH)


def torque_enabled(diagnostics: list[DiagnosticStatus]) -> bool:
    return next(v.value for v in diagnostics[-1].values if v.key == 'torque_enabled') == 'true'


def joint_near(joints: list[JointState], value: float, tolerance: float = 0.05) -> bool:
    return bool(joints) and abs(joints[-1].position[0] - value) < tolerance


def assert_clean_servo(servo: Any) -> None:
    """The servo never saw a goal before its torque was on, nor one outside its bounds."""
    assert 'torque enabled' in servo.output
    assert TORQUE_OFF_WARNING not in servo.output, (
        f'a goal reached the servo with its torque off:\n{servo.output}')
    assert CLAMP_WARNING not in servo.output, f'a goal out of bounds reached the servo:\n{servo.output}'
