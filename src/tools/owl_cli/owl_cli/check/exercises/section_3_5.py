"""Section 3.5: publishers and subscribers (random numbers, a counter, the turtle)."""

from __future__ import annotations

import itertools
import math
import time

from owl_cli.check import criteria as judge
from owl_cli.check.catalogue import Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    CMD_VEL,
    Session,
)

SECTION = Section()


@SECTION.check(
    'random_number_publisher',
    '3.5.3',
    'random_number_ps',
    'publishes a random std_msgs/Int32 from 1 to 100 on random_numbers every second',
)
def check_random_number_publisher(s: Session) -> None:
    """Run random_number_publisher: Int32 on random_numbers, one a second, random, within 1..100."""
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    s.expect_endpoint(
        '/random_numbers',
        'publishers',
        'std_msgs/msg/Int32',
        "no publisher on random_numbers: create_publisher(Int32, 'random_numbers', 10)",
    )
    s.wait(lambda: len(numbers) >= 5, 12.0)
    values = [m.data for _, m in numbers]
    s.add(
        Criterion(
            'publishes numbers on random_numbers',
            len(values) >= 3,
            'fewer than 3 numbers in 12 s: publish from a timer callback',
            f'{len(values)} numbers',
        )
    )
    if len(values) >= 3:
        per_second = judge.rate([t for t, _ in numbers])
        s.add(
            Criterion(
                'publishes one number per second (create_timer(1.0, ...))',
                0.7 <= per_second <= 1.4,
                'the timer period must be 1.0 s',
                f'{per_second:.2f} per second',
            )
        )
        s.add(judge.in_range('the numbers', values, 1, 100, 'random.randint(1, 100) gives 1..100'))
        s.add(
            Criterion(
                'the numbers are random',
                len(set(values)) > 1,
                'every number is the same: draw a new random.randint(1, 100) in each callback',
                f'{values[:6]}',
            )
        )
    s.stop_student()


@SECTION.check(
    'random_number_subscriber',
    '3.5.4',
    'random_number_ps',
    'prints every number it receives on random_numbers',
)
def check_random_number_subscriber(s: Session) -> None:
    """Run random_number_subscriber, publish 17, 42 and 93 to it, and look for them in its output."""
    from std_msgs.msg import Int32

    process = s.student('random_number_ps', 'random_number_subscriber')
    s.expect_endpoint(
        '/random_numbers',
        'subscriptions',
        'std_msgs/msg/Int32',
        "no subscription on random_numbers: create_subscription(Int32, 'random_numbers', callback, 10)",
    )
    publisher = s.node.create_publisher(Int32, '/random_numbers', 10)
    sent = (17, 42, 93)

    def printed() -> bool:
        words = set(process.output.replace(':', ' ').split())
        return all(str(n) in words for n in sent)

    deadline = time.monotonic() + 10.0
    while not printed() and time.monotonic() < deadline and process.running():
        for number in sent:
            publisher.publish(Int32(data=number))
        time.sleep(0.5)
    s.add(
        Criterion(
            'prints every number it receives (17, 42, 93 were published)',
            printed(),
            "log each message in the callback: self.get_logger().info(f'Received: {msg.data}')",
            judge.tail_lines(process.output, 2),
        )
    )
    s.stop_student()


@SECTION.check(
    'counter_publisher',
    '3.5 exercise',
    'random_number_ps',
    'publishes a number that grows by one each time on random_numbers',
)
def check_counter_publisher(s: Session) -> None:
    """Run counter_publisher: the numbers on random_numbers grow by one each time."""
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'counter_publisher')
    s.expect_endpoint(
        '/random_numbers',
        'publishers',
        'std_msgs/msg/Int32',
        "no publisher on random_numbers (the random number subscriber's topic)",
    )
    s.wait(lambda: len(numbers) >= 4, 12.0)
    values = [m.data for _, m in numbers]
    steps = {b - a for a, b in itertools.pairwise(values)}
    s.add(
        Criterion(
            'each number is one more than the one before',
            len(values) >= 3 and steps == {1},
            'keep a counter in the node, publish it and add 1 in each timer callback',
            f'{values[:6]}',
        )
    )
    s.stop_student()


@SECTION.check(
    'turtle_random_velocity',
    '3.5 exercise',
    'random_number_ps',
    "publishes random geometry_msgs/Twist velocities to turtlesim's /turtle1/cmd_vel",
)
def check_turtle_random_velocity(s: Session) -> None:
    """Run turtle_random_velocity beside turtlesim: random Twist velocities on its cmd_vel move the turtle."""
    from geometry_msgs.msg import Twist
    from turtlesim.msg import Pose

    s.helper('turtlesim', 'turtlesim_node', env={'DISPLAY': None, 'WAYLAND_DISPLAY': None})
    poses = s.collect(Pose, '/turtle1/pose')
    twists = s.collect(Twist, CMD_VEL)
    s.student('random_number_ps', 'turtle_random_velocity')
    s.expect_endpoint(
        CMD_VEL, 'publishers', 'geometry_msgs/msg/Twist', "no publisher on turtlesim's /turtle1/cmd_vel"
    )
    s.wait(lambda: len(twists) >= 3, 12.0)
    pairs = {(round(m.linear.x, 3), round(m.angular.z, 3)) for _, m in twists}
    s.add(
        Criterion(
            'the velocities are random (linear.x and angular.z change)',
            len(pairs) >= 2,
            'draw new random numbers in each callback',
            f'{len(twists)} velocities',
        )
    )
    def farthest() -> float:  # from where the turtle was first seen
        return max((math.dist((poses[0][1].x, poses[0][1].y), (p.x, p.y)) for _, p in poses), default=0.0)

    s.wait(lambda: farthest() > 0.2, 5.0)
    distance = farthest()
    s.add(
        Criterion(
            'the turtle moves',
            distance > 0.2,
            'publish non-zero velocities on /turtle1/cmd_vel',
            f'{distance:.2f} m',
        )
    )
    s.stop_student()
