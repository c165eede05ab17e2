"""Section 4.3: the IMU drives the turtle."""

from __future__ import annotations

import math
import time
from typing import Any

from olive_kit.description import IMU_TOPIC

from owl_cli.check import criteria as judge
from owl_cli.check.catalogue import Section
from owl_cli.check.kit_helpers import hold_imu, settle
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    CMD_VEL,
    COURSE_CMD_VEL,
    START_TIMEOUT,
    Session,
    launch_files,
)

SECTION = Section()


SECTION.by_hand(
    'imu_debug_gui',
    '4.3 exercise',
    'olive_imu',
    "the IMU's debug web GUI: watch roll, pitch and yaw while turning the IMU by hand",
    "done by hand on the IMU's web page (the module's or olive_sim's); nothing is left",
)


@SECTION.check(
    'imu_turtle',
    '4.3.2',
    'olive_imu',
    "the IMU's pitch drives the turtle forward, its yaw turns it (/turtle1/cmd_vel)",
)
def check_imu_turtle(s: Session) -> None:
    """Run imu_turtle on the simulated IMU: level it stands still, pitched it drives, turned it turns."""
    from geometry_msgs.msg import Twist

    s.kit('imu', imu_command=True)
    hold_imu(s, 0.0, 0.0, 0.0)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle')
    s.expect_endpoint(
        IMU_TOPIC, 'subscriptions', 'sensor_msgs/msg/Imu', f"no subscription on the IMU's topic {IMU_TOPIC}"
    )
    hint = 'no publisher on /turtle1/cmd_vel: the turtle of turtlesim is turtle1'
    if s.endpoints(COURSE_CMD_VEL, 'publishers'):
        hint = (
            "you publish on /turtle/cmd_vel (the course's text), but turtlesim's turtle is turtle1: "
            'publish on /turtle1/cmd_vel'
        )
    if s.expect_endpoint(CMD_VEL, 'publishers', 'geometry_msgs/msg/Twist', hint) is None:
        s.stop_student()
        return
    if not s.wait(lambda: len(twists) >= 3, 10.0):
        s.add(
            Criterion(
                'publishes velocities while the IMU sends data',
                False,
                'no Twist on /turtle1/cmd_vel in 10 s: publish one for each IMU message (or from a timer)',
            )
        )
        s.stop_student()
        return

    def velocity(m: Any) -> tuple[float, float]:
        return m.linear.x, m.angular.z

    for roll, pitch, yaw, motion in ((0.0, 0.0, 0.0, None), (0.0, 0.4, 0.0, 'pitch'), (0.0, 0.0, 0.5, 'yaw')):
        sent = settle(s, twists, roll, pitch, yaw, velocity, 1.2)
        linear = judge.mean([v[0] for v in sent])
        angular = judge.mean([v[1] for v in sent])
        if not sent:
            s.add(
                Criterion(
                    f'the turtle answers the IMU ({motion or "level"})',
                    False,
                    'no velocity arrived while the IMU held still for 1 s',
                )
            )
        elif motion is None:
            s.add(judge.standing_still(linear, angular))
        else:
            s.add(judge.turtle_response(motion, linear, angular))
    s.stop_student()


@SECTION.check(
    'imu_turtle_launch',
    '4.3.2 +',
    'olive_imu',
    'a launch file of olive_imu that starts turtlesim_node and imu_turtle',
    extra=True,
)
def check_imu_turtle_launch(s: Session) -> None:
    """Launch olive_imu's launch file naming turtlesim and imu_turtle: the scripted IMU moves the turtle."""
    from turtlesim.msg import Pose

    files = [
        f for f in launch_files('olive_imu') if 'imu_turtle' in f.read_text() and 'turtlesim' in f.read_text()
    ]
    if not s.add(
        Criterion(
            'olive_imu installs a launch file that names turtlesim and imu_turtle',
            bool(files),
            'a launch file in olive_imu/launch, installed through data_files in setup.py',
            ', '.join(f.name for f in files),
        )
    ):
        return
    s.kit('imu')  # the scripted motion: pitch and yaw sweep
    poses = s.collect(Pose, '/turtle1/pose')
    s.student_launch('olive_imu', files[0].name)
    s.wait(lambda: len(poses) >= 10, 20.0)
    start = (poses[0][1].x, poses[0][1].y) if poses else None
    s.wait(lambda: start is not None and math.dist(start, (poses[-1][1].x, poses[-1][1].y)) > 0.2, 10.0)
    distance = math.dist(start, (poses[-1][1].x, poses[-1][1].y)) if start else 0.0
    s.add(
        Criterion(
            f'ros2 launch olive_imu {files[0].name} starts turtlesim and the IMU drives the turtle',
            distance > 0.2,
            'no turtle pose arrived' if start is None else 'the turtle did not move',
            f'{distance:.2f} m',
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)


@SECTION.check(
    'imu_turtle_speed',
    '4.3.2 +',
    'olive_imu',
    "a parameter of imu_turtle that adjusts the turtle's speed",
    extra=True,
)
def check_imu_turtle_speed(s: Session) -> None:
    """Run imu_turtle and try its numeric parameters in turn: one must change the turtle's speed.

    Each is doubled (or set to 1 from 0) while the IMU is pitched, then set back; a change of more
    than 30 % in linear.x counts.
    """
    from geometry_msgs.msg import Twist

    s.kit('imu', imu_command=True)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle')
    s.wait(lambda: len(twists) >= 3 and 'imu_turtle' in s.node.get_node_names(), START_TIMEOUT)

    def speed() -> float:
        return judge.mean([v[0] for v in settle(s, twists, 0.0, 0.4, 0.0, lambda m: (m.linear.x,), 1.2)])

    before = speed()
    found, detail = None, []
    for name, value in s.own_parameters('imu_turtle').items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            continue
        changed = type(value)(value * 2 if value else 1)
        ok, _ = s.set_parameter('imu_turtle', name, changed)
        if not ok:
            continue
        after = speed()
        s.set_parameter('imu_turtle', name, value)
        detail.append(f'{name} {value}->{changed}: {before:.2f}->{after:.2f} m/s')
        if abs(before) > judge.STILL and abs(after - before) > 0.3 * abs(before):
            found = name
            break
    s.add(
        Criterion(
            "a parameter changes the turtle's speed while it runs (ros2 param set)",
            found is not None,
            "declare_parameter('speed', 1.0) and multiply linear.x by self.get_parameter('speed').value "
            'in the callback',
            '; '.join(detail) or 'no numeric parameter',
        )
    )
    s.stop_student()


OTHER_IMU_TOPIC = '/owl_check/imu'


def feed_imu(s: Session, topic: str, pitch: float, seconds: float) -> None:
    """Publish the IMU's messages ourselves on a topic of our choice, 20 per second."""
    from owl_common.quaternion import from_euler
    from sensor_msgs.msg import Imu

    publisher = s.node.create_publisher(Imu, topic, 10)
    message = Imu()
    message.header.frame_id = 'imu'
    x, y, z, w = from_euler(0.0, pitch, 0.0)
    message.orientation.x, message.orientation.y, message.orientation.z, message.orientation.w = x, y, z, w
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        publisher.publish(message)
        time.sleep(0.05)


@SECTION.check(
    'imu_turtle_topic',
    '4.3.2 +',
    'olive_imu',
    "a parameter of imu_turtle for the name of the IMU's topic",
    extra=True,
)
def check_imu_turtle_topic(s: Session) -> None:
    """Run imu_turtle: a parameter holds the IMU's topic, and set to another topic it follows that one."""
    from geometry_msgs.msg import Twist

    process = s.student('olive_imu', 'imu_turtle')
    s.wait(lambda: 'imu_turtle' in s.node.get_node_names(), START_TIMEOUT)
    names = [name for name, value in s.own_parameters('imu_turtle').items() if value == IMU_TOPIC]
    s.stopped = True  # our own stop: its exit is no crash
    process.stop(3.0)
    if not s.add(
        Criterion(
            f"a string parameter of imu_turtle holds the IMU's topic (default {IMU_TOPIC})",
            bool(names),
            f"declare_parameter('imu_topic', '{IMU_TOPIC}') and subscribe to "
            "self.get_parameter('imu_topic').value",
            ', '.join(names),
        )
    ):
        return
    s.wait(lambda: 'imu_turtle' not in s.node.get_node_names(), 3.0)
    twists = s.collect(Twist, CMD_VEL)
    s.student('olive_imu', 'imu_turtle', '--ros-args', '-p', f'{names[0]}:={OTHER_IMU_TOPIC}')
    s.stopped = False
    s.expect_endpoint(
        OTHER_IMU_TOPIC,
        'subscriptions',
        'sensor_msgs/msg/Imu',
        f'with -p {names[0]}:={OTHER_IMU_TOPIC} nothing subscribes there: create the subscription with '
        'the parameter\'s value',
    )
    old = s.endpoints(IMU_TOPIC, 'subscriptions')
    s.add(
        Criterion(
            f'it no longer subscribes to {IMU_TOPIC}',
            not old,
            'the subscription still uses the fixed topic: use the parameter\'s value instead',
        )
    )
    start = time.monotonic()
    feed_imu(s, OTHER_IMU_TOPIC, 0.4, 2.0)
    speeds = [m.linear.x for t, m in twists if t >= start + 1.0]
    s.add(
        Criterion(
            f'the IMU on {OTHER_IMU_TOPIC} (pitched 0.4 rad) drives the turtle forward',
            judge.mean(speeds) > judge.STILL,
            'no forward velocity from the IMU on the new topic',
            f'linear.x {judge.mean(speeds):+.2f} from {len(speeds)} messages',
        )
    )
    s.stop_student()
