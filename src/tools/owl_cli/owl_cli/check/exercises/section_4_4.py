"""Section 4.4 and appendix 5.3: the servos' goals, torque and PID."""

from __future__ import annotations

import time

from olive_kit.description import goal_topic, servo_topic

from owl_cli.check import criteria as judge
from owl_cli.check.catalogue import TERMINAL, Section
from owl_cli.check.kit_helpers import joint_positions, moved, numeric_parameters, scaled, torque_criterion
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    PAN_RANGE,
    START_TIMEOUT,
    Session,
)

SECTION = Section()


SECTION.by_hand(
    'pid_tuning',
    '4.4 exercises',
    'olive_servo',
    "tune the pan servo's Kp, Ki, Kd with ros2 param set and watch the overshoot",
    TERMINAL,
)


@SECTION.check(
    'pid_testing',
    '4.4, 5.3',
    'olive_servo',
    'appendix 5.3: enables the pan torque, then goals 1.57 and 0.0 rad every 3 s',
)
def check_pid_testing(s: Session) -> None:
    """Run pid_testing on the simulated pan servo: torque on, goals 1.57 and 0.0 rad every 3 s, it turns."""
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'pid_testing')
    s.expect_endpoint(
        goal_topic('pan'), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic("pan")}'
    )
    s.wait(lambda: len({round(m.data, 2) for _, m in goals}) >= 2, 12.0)
    values = [round(m.data, 2) for _, m in goals]
    s.add(
        Criterion(
            'the goal alternates between 1.57 and 0.0 rad',
            set(values) == {1.57, 0.0},
            'publish 1.57, then 0.0, then 1.57 ... from create_timer(3.0, ...)',
            f'goals {values[:6]}',
        )
    )
    stamps = [t for t, _ in goals]
    period = (stamps[-1] - stamps[0]) / (len(stamps) - 1) if len(stamps) >= 2 else 0.0
    s.add(
        Criterion(
            'a new goal every 3 s',
            2.5 <= period <= 3.5,
            'create_timer(3.0, self.publish_goal)',
            f'every {period:.1f} s' if period else 'fewer than 2 goals',
        )
    )
    torque_criterion(s, 'pan', goals)
    swing = moved(joints)
    s.add(
        Criterion(
            'the pan servo turns to the goals',
            swing >= 1.0,
            'the servo does not follow the goals',
            f'it turned {swing:.2f} rad',
        )
    )
    s.stop_student()


@SECTION.check(
    'control_servo',
    '4.4',
    'olive_servo',
    'enables the pan torque, then publishes a sine of goal positions every 0.01 s',
)
def check_control_servo(s: Session, torque_off_only: bool = False) -> None:
    """Run control_servo on the simulated pan servo: a sine of goals, then the torque off at Ctrl-C.

    With torque_off_only (the extra control_servo_torque_off) only the last criterion is added.
    """
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'control_servo')
    if not torque_off_only:
        s.expect_endpoint(
            goal_topic('pan'), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic("pan")}'
        )
    s.wait(lambda: len(goals) >= 20, START_TIMEOUT)
    start = time.monotonic()
    s.wait(lambda: judge.oscillates([m.data for _, m in goals]), 8.0)
    if torque_off_only:
        s.wait(lambda: 'torque enabled' in s.helpers['pan'].output, 2.0)
    else:
        values = [m.data for _, m in goals]
        per_second = judge.rate([t for t, _ in goals if t >= start])
        s.add(
            Criterion(
                'publishes goals at least 10 times per second (the course starts at every 0.01 s)',
                per_second >= 10.0,
                'publish from create_timer(0.01, ...)',
                f'{per_second:.0f} per second',
            )
        )
        s.add(
            Criterion(
                'the goals follow a sine (they swing and turn back)',
                judge.oscillates(values),
                'add a small step to a variable in each callback and publish math.sin(variable)',
                f'{len(values)} goals from {min(values, default=0):+.2f} to {max(values, default=0):+.2f}',
            )
        )
        s.add(
            judge.in_range(
                'the goals',
                values,
                *PAN_RANGE,
                "keep the sine's amplitude within the pan servo's ±1.5708 rad",
            )
        )
        torque_criterion(s, 'pan', goals)
        swing = moved(joints)
        s.add(
            Criterion(
                'the pan servo moves',
                swing >= 0.2,
                'the servo does not follow the goals',
                f'it swung {swing:.2f} rad',
            )
        )
    s.stop_student()
    text = 'Ctrl-C disables the pan torque (setTorqueDisable) before the node ends'
    disabled = s.wait(lambda: 'torque disabled' in s.helpers['pan'].output, 2.0)
    s.add(
        Criterion(
            text,
            disabled,
            f"catch KeyboardInterrupt and call {servo_topic('pan', 'setTorqueDisable')} (on a ROS 2 "
            "install of your own, Jazzy's Ctrl-C handler shuts ROS down first: there use "
            'rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO))',
        )
    )


@SECTION.check(
    'control_servo_torque_off',
    '4.4 +',
    'olive_servo',
    'control_servo disables the torque when it is stopped with Ctrl-C',
    extra=True,
)
def check_control_servo_torque_off(s: Session) -> None:
    """Run control_servo and stop it with Ctrl-C: it must disable the pan servo's torque first."""
    check_control_servo(s, torque_off_only=True)


@SECTION.check(
    'control_servo_frequency',
    '4.4 +',
    'olive_servo',
    'a parameter of control_servo for the publishing frequency',
    extra=True,
)
def check_control_servo_frequency(s: Session) -> None:
    """Run control_servo and halve its numeric parameters in turn: one must change the goals' rate.

    Those named like a frequency or period come first; a change of more than 30 % counts.
    """
    from std_msgs.msg import Float32

    s.kit('pan')
    goals = s.collect(Float32, goal_topic('pan'))
    s.student('olive_servo', 'control_servo')
    s.wait(lambda: len(goals) >= 20 and 'control_servo' in s.node.get_node_names(), START_TIMEOUT)

    def measured_rate(settle: float = 0.3) -> float:
        start = time.monotonic() + settle  # a new period takes effect from the timer's next call
        s.wait(lambda: time.monotonic() > start + 1.2, 2.0)
        return judge.rate([t for t, _ in goals if t >= start])

    before = measured_rate(0.0)  # nothing was set yet: the node has published at this rate all along
    found, detail = None, []
    for name, value in numeric_parameters(s, 'control_servo', ('freq', 'rate', 'period', 'hz')):
        changed = scaled(value, 0.5)
        ok, _ = s.set_parameter('control_servo', name, changed)
        if not ok:
            continue
        after = measured_rate()
        s.set_parameter('control_servo', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.0f}->{after:.0f} goals/s')
        if before > 0 and abs(after - before) > 0.3 * before:
            found = name
            break
        before = measured_rate()
    s.add(
        Criterion(
            'a parameter changes the publishing frequency while it runs (ros2 param set)',
            found is not None,
            "declare_parameter('frequency', 100.0) and change the timer's period when it is set "
            '(add_post_set_parameters_callback), or read it when the timer is created',
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()
