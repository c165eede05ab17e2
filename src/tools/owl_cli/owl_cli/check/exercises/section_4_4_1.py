"""Section 4.4.1: the keyboard and the IMU move the pan/tilt head."""

from __future__ import annotations

import itertools
import time
from collections.abc import Callable
from pathlib import Path

from olive_kit.description import IMU_TOPIC, goal_topic, servo_topic
from owl_common.processes import RosProcess

from owl_cli.check import criteria as judge
from owl_cli.check.catalogue import Section
from owl_cli.check.kit_helpers import (
    hold_imu,
    joint_positions,
    moved,
    numeric_parameters,
    scaled,
    settle,
    torque_criterion,
)
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    PAN_RANGE,
    START_TIMEOUT,
    TILT_RANGE,
    Session,
)

SECTION = Section()


def press(s: Session, process: RosProcess, *events: str) -> bool:
    """Key events ('down left', 'up left') for the node's headless pygame window (owl_gui_hook)."""
    windows = Path(s.temporary.name)
    folders = list(windows.glob('*-*'))
    if not folders:
        return False
    with open(folders[0] / 'keys', 'a') as keys:
        for event in events:
            keys.write(event + '\n')
    return True


# A held key's goals count as stopped once they stayed one value (within GOAL_STEADY rad) for STEADY_FOR
# s, the value they had just before too; not before HELD_AT_LEAST s, the node's time to see the key.
STEADY_FOR, GOAL_STEADY, HELD_AT_LEAST = 0.5, 1e-3, 1.0  # s, rad, s
KEY_SWING = 0.3  # rad the goal must swing across a pair of keys (Left and Right, Up and Down)


# A held key's speed is the slope of at least SPEED_GOALS goals over at least SPEED_FOR s, counted from
# the first goal that moved: however late a loaded machine delivers the key, no still goal dilutes it.
SPEED_GOALS, SPEED_FOR = 8, 0.5  # goals, s


def moving_goals(goals: list, still: float) -> list[tuple[float, float]]:
    """(time, value) of a servo's goals (Session.collect pairs) from the first that left the value still."""
    values = [(t, m.data) for t, m in goals]
    first = next((i for i, (_, v) in enumerate(values) if abs(v - still) > GOAL_STEADY), len(values))
    return values[first:]


def held_long_enough(samples: list[tuple[float, float]]) -> bool:
    """Whether a held key's moving goals are enough to measure its speed on (SPEED_GOALS, SPEED_FOR)."""
    return len(samples) >= SPEED_GOALS and samples[-1][0] - samples[0][0] >= SPEED_FOR


def goals_stopped(goals: list, now: float) -> bool:
    """Whether a servo's goals (Session.collect pairs) of the last STEADY_FOR s stayed one value.

    That value must be the one of the 0.2 s before them too, so a servo that sent nothing lately
    has not stopped.
    """
    recent = [m.data for t, m in goals if t >= now - STEADY_FOR]
    earlier = [m.data for t, m in goals if now - STEADY_FOR - 0.2 <= t < now - STEADY_FOR]
    return (
        bool(recent)
        and bool(earlier)
        and max(recent) - min(recent) < GOAL_STEADY
        and abs(recent[-1] - earlier[-1]) < GOAL_STEADY
    )


def beyond_and_swung(held: list[float], other: list[float], low: float, high: float) -> bool:
    """Whether holding a key longer can change neither verdict on its servo's goals.

    held: the goals since the key went down, other: those while the opposite key was held. When
    held already left low..high, bounded_goal fails whatever comes after; when held and other
    already swing KEY_SWING, the key moves the goal whatever comes after.
    """
    if not held or judge.bounded_goal('', held, low, high, '').passed:
        return False
    both = held + other
    return max(both) - min(both) >= KEY_SWING


def hold_keys(
    s: Session,
    process: RosProcess,
    keys: tuple[str, ...],
    goals: dict[str, list],
    decided: Callable[[str, float], bool] | None = None,
    longest: float = 5.0,
) -> float:
    """Hold keys until each servo's goals stopped changing or decided(servo, start) (or longest s).

    Return when it started. Each servo's goals are looked at on their own: pan and tilt stop at
    limits of their own, never at one value.
    """
    start = time.monotonic()
    press(s, process, *(f'down {k}' for k in keys))

    def done(servo: str) -> bool:
        if decided is not None and decided(servo, start):
            return True
        now = time.monotonic()
        return now - start >= HELD_AT_LEAST and goals_stopped(goals[servo], now)

    s.wait(lambda: all(done(servo) for servo in goals), longest)
    press(s, process, *(f'up {k}' for k in keys))
    return start


@SECTION.check(
    'keyboard_servos',
    '4.4.1',
    'olive_servo',
    'arrow keys move the pan (left/right) and tilt (up/down) goals, within bounds',
)
def check_keyboard_servos(s: Session) -> None:
    """Run keyboard_servos with a headless window: held arrow keys move pan and tilt goals, within bounds."""
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    process = s.student(
        'olive_servo',
        'keyboard_servos',
        env={
            'DISPLAY': None,
            'WAYLAND_DISPLAY': None,
            'OWL_HEADLESS': '1',
            'OWL_WINDOWS_DIR': s.temporary.name,
        },
    )
    for servo in ('pan', 'tilt'):
        s.expect_endpoint(
            goal_topic(servo), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic(servo)}'
        )
    window = s.wait(lambda: press(s, process), START_TIMEOUT)
    if not s.add(
        Criterion(
            'opens a pygame window for the keys',
            window,
            'pygame.display.set_mode(...) gives the window whose keys move the servos',
        )
    ):
        s.stop_student()
        return
    s.wait(lambda: all(len(g) >= 5 for g in goals.values()), 5.0)
    ranges = {'pan': PAN_RANGE, 'tilt': TILT_RANGE}
    held: dict[str, list[list[float]]] = {'pan': [], 'tilt': []}  # each servo's goals for each pair of keys

    def decided(servo: str, start: float) -> bool:
        values = [m.data for t, m in goals[servo] if t >= start]
        return beyond_and_swung(values, held[servo][0], *ranges[servo])

    # The second keys start from where the first left the goals: only the second may end early on
    # decided verdicts (the first end only once the goals stopped).
    for keys, early in ((('left', 'up'), None), (('right', 'down'), decided)):
        start = hold_keys(s, process, keys, goals, early)
        for servo, key in zip(('pan', 'tilt'), keys, strict=True):
            values = [m.data for t, m in goals[servo] if t >= start]
            held[servo].append(values)
            s.add(judge.bounded_goal(servo, values, *ranges[servo], f'{key.title()} is held'))
    for servo, keys in (('pan', ('left', 'right')), ('tilt', ('up', 'down'))):
        both = held[servo][0] + held[servo][1]
        swing = (max(both) - min(both)) if both else 0.0
        s.add(
            Criterion(
                f'{keys[0].title()}/{keys[1].title()} move the {servo} goal',
                swing >= KEY_SWING,
                f'holding {keys[0].title()} and {keys[1].title()} left the {servo} goal where it was: '
                'read pygame.key.get_pressed() in the timer callback',
                f'it swung {swing:.2f} rad',
            )
        )
    s.stop_student()


KEYBOARD_ENV_KEYS = ('DISPLAY', 'WAYLAND_DISPLAY')


def start_keyboard_servos(s: Session) -> RosProcess:
    """Start the student's keyboard_servos with its pygame window headless, in the session's folder."""
    env: dict[str, str | None] = {key: None for key in KEYBOARD_ENV_KEYS}
    env.update({'OWL_HEADLESS': '1', 'OWL_WINDOWS_DIR': s.temporary.name})
    return s.student('olive_servo', 'keyboard_servos', env=env)


@SECTION.check(
    'keyboard_servos_torque',
    '4.4.1 +',
    'olive_servo',
    "keyboard_servos enables both servos' torque at start and disables it when it stops",
    extra=True,
)
def check_keyboard_servos_torque(s: Session) -> None:
    """Run keyboard_servos: both servos' torque on before their goals, and off again at Ctrl-C."""
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    start_keyboard_servos(s)
    s.wait(lambda: all(len(g) >= 5 for g in goals.values()), START_TIMEOUT)
    for servo in ('pan', 'tilt'):
        torque_criterion(s, servo, goals[servo])
    s.stop_student()
    disabled = s.wait(lambda: all('torque disabled' in s.helpers[v].output for v in ('pan', 'tilt')), 2.0)
    s.add(
        Criterion(
            'Ctrl-C disables the pan and tilt torque (setTorqueDisable) before the node ends',
            disabled,
            f"after rclpy.spin, call {servo_topic('pan', 'setTorqueDisable')} and "
            f"{servo_topic('tilt', 'setTorqueDisable')}; "
            "(on a ROS 2 install of your own, Jazzy's Ctrl-C handler shuts ROS down first: there use "
            'rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO))',
            ', '.join(v for v in ('pan', 'tilt') if 'torque disabled' in s.helpers[v].output),
        )
    )


@SECTION.check(
    'keyboard_servos_speed',
    '4.4.1 +',
    'olive_servo',
    'a parameter of keyboard_servos that adjusts the speed of the servos',
    extra=True,
)
def check_keyboard_servos_speed(s: Session) -> None:
    """Run keyboard_servos and double its numeric parameters in turn: one must change a held key's speed.

    Those named like a speed or step come first, bounds are skipped; the speed is the pan goal's
    rate of change while Left or Right is held, and a change of more than 30 % counts.
    """
    from std_msgs.msg import Float32

    s.kit('pan', 'tilt')
    pan = s.collect(Float32, goal_topic('pan'))
    process = start_keyboard_servos(s)
    window = s.wait(lambda: press(s, process) and len(pan) >= 5, START_TIMEOUT)
    if not s.add(
        Criterion(
            'opens a pygame window and publishes pan goals',
            window,
            'pygame.display.set_mode(...) gives the window whose keys move the servos',
        )
    ):
        s.stop_student()
        return
    keys = itertools.cycle(('left', 'right'))

    def speed() -> float:
        key, seen, still = next(keys), len(pan), pan[-1][1].data
        press(s, process, f'down {key}')
        s.wait(lambda: held_long_enough(moving_goals(pan[seen:], still)), START_TIMEOUT)
        press(s, process, f'up {key}')
        samples = moving_goals(pan[seen:], still)
        return judge.slope([(t, v) for t, v in samples if PAN_RANGE[0] + 0.01 < v < PAN_RANGE[1] - 0.01])

    before = speed()
    found, detail = None, []
    for name, value in numeric_parameters(s, 'keyboard_servos', ('speed', 'step', 'vel', 'rate', 'gain')):
        if any(word in name.lower() for word in ('min', 'max', 'limit', 'bound')):
            continue  # the goals' bounds, not their speed
        changed = scaled(value, 2.0)
        ok, _ = s.set_parameter('keyboard_servos', name, changed)
        if not ok:
            continue
        after = speed()
        s.set_parameter('keyboard_servos', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.2f}->{after:.2f} rad/s')
        if before > judge.STILL and abs(after - before) > 0.3 * before:
            found = name
            break
        before = speed()
    s.add(
        Criterion(
            'a parameter changes how fast a held key moves the servo (ros2 param set)',
            found is not None,
            "declare_parameter('speed', 1.0) and scale each step of the goal by "
            "self.get_parameter('speed').value in the timer callback",
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()


@SECTION.check(
    'imu_control_robot',
    '4.4.1',
    'olive_servo',
    'the IMU points the pan/tilt head: goals follow yaw and pitch, within bounds',
)
def check_imu_control_robot(s: Session) -> None:
    """Run imu_control_robot on the simulated IMU: pan follows yaw, tilt follows pitch, within bounds."""
    from std_msgs.msg import Float32

    s.kit('imu', 'pan', 'tilt', imu_command=True)
    hold_imu(s, 0.0, 0.0, 0.0)
    goals = {servo: s.collect(Float32, goal_topic(servo)) for servo in ('pan', 'tilt')}
    joints = joint_positions(s, 'pan')
    s.student('olive_servo', 'imu_control_robot')
    s.expect_endpoint(IMU_TOPIC, 'subscriptions', 'sensor_msgs/msg/Imu', f'no subscription on {IMU_TOPIC}')
    for servo in ('pan', 'tilt'):
        s.expect_endpoint(
            goal_topic(servo), 'publishers', 'std_msgs/msg/Float32', f'no publisher on {goal_topic(servo)}'
        )
    s.wait(lambda: all(len(g) >= 3 for g in goals.values()), 10.0)

    def last(servo: str, since: float) -> float | None:
        values = [m.data for t, m in goals[servo] if t >= since]
        return judge.mean(values[-5:]) if values else None

    results = {}
    for name, (pitch, yaw) in {'yaw': (0.0, 0.6), 'pitch': (0.5, 0.0)}.items():
        start = time.monotonic()
        settle(s, goals['pan'], 0.0, pitch, yaw, lambda m: (m.data,), 1.2)
        results[name] = (last('pan', start + 0.6), last('tilt', start + 0.6))
    pan_yaw, tilt_yaw = results['yaw']
    pan_pitch, tilt_pitch = results['pitch']
    if pan_yaw is None or tilt_yaw is None or pan_pitch is None or tilt_pitch is None:
        s.add(
            Criterion(
                'sends pan and tilt goals while the IMU turns',
                False,
                'publish a goal for each servo from each IMU message (or a timer)',
            )
        )
    else:
        s.add(
            Criterion(
                'the pan goal follows the yaw (turning the IMU left turns the head left)',
                abs(pan_yaw - 0.6) <= 0.15 and abs(pan_pitch) <= 0.15,
                'pan must be the yaw angle and tilt the pitch angle from equations (3); check which '
                'angle goes to which servo and its sign',
                f'pan {pan_yaw:+.2f} rad at yaw +0.60, {pan_pitch:+.2f} rad at pitch +0.50',
            )
        )
        s.add(
            Criterion(
                'the tilt goal follows the pitch (tilting the IMU forward tilts the camera down)',
                abs(tilt_pitch - 0.5) <= 0.15 and abs(tilt_yaw) <= 0.15,
                'tilt must be the pitch angle from equations (3); check which angle goes to which '
                'servo and its sign',
                f'tilt {tilt_pitch:+.2f} rad at pitch +0.50, {tilt_yaw:+.2f} rad at yaw +0.60',
            )
        )
    start = time.monotonic()
    settle(s, goals['pan'], 0.0, 1.4, 2.6, lambda m: (m.data,), 1.5)
    for servo, range_ in (('pan', PAN_RANGE), ('tilt', TILT_RANGE)):
        values = [m.data for t, m in goals[servo] if t >= start]
        s.add(judge.bounded_goal(servo, values, *range_, 'the IMU turns far (yaw 2.6, pitch 1.4 rad)'))
    torque_criterion(s, 'pan', goals['pan'])
    swing = moved(joints)
    s.add(
        Criterion(
            'the pan servo moves with the IMU',
            swing >= 0.3,
            'the servo does not follow the goals',
            f'it turned {swing:.2f} rad',
        )
    )
    s.stop_student()
