"""What the robot view shows of the kit, as plain data (node-free).

The joint angles and the IMU's orientation, the commands a page may send to hold the simulated
IMU, which modules run and what steers them, and what came of a goal.
"""

from __future__ import annotations

from typing import Any

from olive_kit.description import CAMERA_TOPIC, IMU_NAMESPACE, IMU_TOPIC, joint_topic, node_name, servo_topic
from owl_web import codec

from robot_view.controls import SERVOS

# The simulated IMU listens here only with motion:=command (robot_view.launch.py starts it so).
TRUE_ORIENTATION_TOPIC = f"/{node_name('imu', IMU_NAMESPACE)}/true_orientation"

LEVEL = (0.0, 0.0, 0.0, 1.0)  # x, y, z, w: the IMU lying flat, pointing along base_link's x
# s after robot_view starts during which a module not seen yet is not said to be missing: the
# launch starts the modules beside robot_view, and on a loaded machine its first look at 1 s found
# some still starting, so a "Not running" line came and went and the page shifted under the mouse.
STARTUP_GRACE = 3.0
# s without a message from a module after which the page greys what it shows of it. The kit's
# modules publish 30-100 times a second; the graph says a module went only when DDS does (a killed
# process: after its lease, about 10 s), the data says it within a second.
SILENT_AFTER = 1.0
MODULE_NAMES = {'imu': 'the IMU', 'pan': 'the pan servo', 'tilt': 'the tilt servo', 'camera': 'the camera'}


def hold_imu_orientation(arguments: dict[str, Any]) -> tuple[float, float, float, float]:
    """The orientation of a page's "hold_imu" command ({"orientation": {x, y, z, w}})."""
    codec.check_keys(arguments, ('orientation',), required=('orientation',))
    return codec.unit_quaternion(arguments['orientation'])


def level_orientation(arguments: dict[str, Any]) -> tuple[float, float, float, float]:
    """A "level" command takes no arguments."""
    codec.check_keys(arguments, ())
    return LEVEL


def joint_position(names: list[str], positions: list[float], joint: str) -> float | None:
    """The position of `joint` in a JointState's names/positions, or None when it is not there."""
    for name, position in zip(names, positions, strict=False):
        if name == joint:
            return float(position)
    return None


def kit_presence(publishers: dict[str, int], subscribers: dict[str, int],
                 steering: dict[str, list[str]] | None = None) -> dict[str, Any]:
    """Which modules run and what steers them, from the graph's publisher and subscriber counts by topic.

    modules: each module publishes (a servo its joint, the IMU, the camera); imu_steerable: a
    simulated IMU takes the page's orientation (it subscribes to true_orientation; a scripted one or a
    real module does not); steered: servo -> the nodes other than robot_view that publish its goals
    (steering, e.g. ['/imu_control_robot']), sorted.
    """
    modules = {servo: publishers.get(joint_topic(servo), 0) > 0 for servo in SERVOS}
    modules['imu'] = publishers.get(IMU_TOPIC, 0) > 0
    modules['camera'] = publishers.get(CAMERA_TOPIC, 0) > 0
    steering = steering or {}
    return {'modules': modules,
            'imu_steerable': subscribers.get(TRUE_ORIENTATION_TOPIC, 0) > 0,
            'steered': {servo: sorted(set(steering.get(servo, []))) for servo in SERVOS}}


def first_presence_due(presence: dict[str, Any], since_start: float) -> bool:
    """Whether robot_view says its first look's kit_presence, since_start s after it started.

    At once when every module runs; otherwise once STARTUP_GRACE has passed (then the missing ones
    are named). Later changes are said at once: a module that stops is missing.
    """
    return all(presence['modules'].values()) or since_start >= STARTUP_GRACE


def servo_unavailable(servo: str, silent_for: int | None, heard: bool) -> str | None:
    """Why a command to the servo cannot act: it never sent a joint state, or none for silent_for s.

    None when it can (its joint states come).
    """
    if not heard:
        return (f'{MODULE_NAMES[servo]} has sent no joint state: is it running? The simulated kit: '
                'ros2 launch olive_sim owl_kit.launch.py')
    if silent_for is not None:
        return f'no data from {MODULE_NAMES[servo]} for {silent_for} s: has it stopped?'
    return None


def goal_outcome(servo: str, torque: bool | None, steered_by: list[str] | None = None) -> dict[str, Any]:
    """What came of a goal sent to a servo whose torque is as its diagnostics last said (None: not known).

    A servo with its torque off ignores every goal (it says so in its log). A goal the servo takes
    while other nodes publish its goals too (steered_by, e.g. imu_control_robot 100 times a second)
    is overridden by their next one. Otherwise it is sent, and whether it is reached shows in the
    servo's joint.
    """
    if torque is False:
        return {'outcome': 'ignored',
                'reason': f"the {servo} servo's torque is off, so it ignores goals: switch it on "
                          f"(torque column, or {servo_topic(servo, 'setTorqueEnable')}) first"}
    if steered_by:
        nodes = ' and '.join(steered_by)
        return {'outcome': 'overridden', 'by': list(steered_by),
                'reason': f"{nodes} also publish{'es' if len(steered_by) == 1 else ''} the {servo} "
                          f"servo's goals, and {'its' if len(steered_by) == 1 else 'their'} next goal "
                          'replaces this one: stop it (Ctrl-C in its terminal) to steer the servo from here'}
    return {'outcome': 'sent'}


def silences(last_heard: dict[str, float], now: float) -> dict[str, int]:
    """Whole seconds since each module's last message, for the modules silent SILENT_AFTER s or more.

    last_heard: module -> the monotonic time of its last message; a module never heard is not in it
    (whether it runs at all is the graph's to say, kit_presence).
    """
    return {module: int(now - heard) for module, heard in last_heard.items() if now - heard >= SILENT_AFTER}
