"""What several sections' checks share: the IMU held in a pose, servos, numeric parameters.

The simulated IMU turned and held (hold_imu, settle), the servos' joint states and torque
(joint_positions, moved, torque_criterion), a node's numeric parameters (numeric_parameters, scaled).
The exercise plug-ins import these from here, never from each other, so each section's module
stands alone.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from olive_kit.description import joint_topic, servo_topic

from owl_cli.check.report import Criterion
from owl_cli.check.session import IMU_COMMAND_TOPIC, Session


def hold_imu(s: Session, roll: float, pitch: float, yaw: float) -> None:
    """Turn the simulated IMU (motion:=command) to roll, pitch and yaw in rad: one message to imu_sim."""
    from geometry_msgs.msg import Quaternion
    from owl_common.quaternion import from_euler

    x, y, z, w = from_euler(roll, pitch, yaw)
    publisher = s.imu_command_publisher
    if publisher is None:
        publisher = s.imu_command_publisher = s.node.create_publisher(Quaternion, IMU_COMMAND_TOPIC, 10)
    publisher.publish(Quaternion(x=x, y=y, z=z, w=w))


def settle(
    s: Session,
    received: list,
    roll: float,
    pitch: float,
    yaw: float,
    value: Callable[[Any], tuple[float, ...]],
    seconds: float = 1.0,
) -> list[tuple[float, ...]]:
    """Hold the IMU there (sent again each 0.2 s), and return what the node sent in the last half."""
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        hold_imu(s, roll, pitch, yaw)
        time.sleep(0.2)
    since = start + seconds / 2
    return [value(m) for t, m in received if t >= since]


TORQUE_OFF_WARNING = 'ignored, torque is disabled'


def torque_criterion(s: Session, servo: str, goals: list) -> None:
    """Add the criterion that the node enabled the servo's torque before its first goal.

    Read from the simulated servo's log: 'torque enabled', and no goal ignored while it was off.
    """
    log = s.helpers[servo].output
    enabled = 'torque enabled' in log
    early = TORQUE_OFF_WARNING in log
    if not enabled:
        hint = (
            f'the {servo} servo ignores every goal while its torque is off: call '
            f"{servo_topic(servo, 'setTorqueEnable')} (std_srvs/srv/Trigger) before the first goal"
        )
    else:
        hint = (
            f'goals reached the {servo} servo before its torque was on and were ignored: call '
            'setTorqueEnable and wait for its answer before publishing goals'
        )
    s.add(
        Criterion(
            f'enables the {servo} torque (setTorqueEnable) before sending goals',
            enabled and not early,
            hint,
            f'{len(goals)} goals',
        )
    )


def joint_positions(s: Session, servo: str) -> list:
    """The servo's JointState messages from now on, as (monotonic time, message) pairs (Session.collect)."""
    from sensor_msgs.msg import JointState

    return s.collect(JointState, joint_topic(servo))


def moved(joints: list, since: float = 0.0) -> float:
    """How far (rad) the servo's position spanned in the joint states from monotonic time since on."""
    values = [m.position[0] for t, m in joints if t >= since and m.position]
    return max(values) - min(values) if values else 0.0


def numeric_parameters(s: Session, node: str, preferred: tuple[str, ...]) -> list[tuple[str, float]]:
    """(name, value) of a node's own numeric parameters, those naming a preferred word first."""
    found = [
        (name, value)
        for name, value in s.own_parameters(node).items()
        if isinstance(value, (int, float)) and not isinstance(value, bool)
    ]
    return sorted(found, key=lambda item: not any(word in item[0].lower() for word in preferred))


def scaled(value: float, factor: float) -> float:
    """The parameter value times factor, an int staying an int of at least 1; 1 for a value of 0."""
    if isinstance(value, int):
        return max(1, round(value * factor)) if value else 1
    return value * factor if value else 1.0
