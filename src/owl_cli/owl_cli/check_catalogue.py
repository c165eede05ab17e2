"""The exercises and projects of course sections 3.4 to 4.5 that leave code in a workspace.

Each has an id (the course's executable name where there is one, else a short name), its section,
the package it lives in and a one-line description. Exercises typed at a terminal (3.6.1's service
calls, 3.7.1's colour changes, 3.8's action goals) leave nothing in a workspace to check.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass


@dataclass(frozen=True)
class Exercise:
    id: str
    section: str
    package: str
    description: str
    extra: bool = False  # one of the course's "+" extras


EXERCISES: tuple[Exercise, ...] = (
    Exercise(
        'random_number_publisher',
        '3.5.3',
        'random_number_ps',
        'publishes a random std_msgs/Int32 from 1 to 100 on random_numbers every second',
    ),
    Exercise(
        'random_number_subscriber',
        '3.5.4',
        'random_number_ps',
        'prints every number it receives on random_numbers',
    ),
    Exercise(
        'counter_publisher',
        '3.5 exercise',
        'random_number_ps',
        'publishes a number that grows by one each time on random_numbers',
    ),
    Exercise(
        'turtle_random_velocity',
        '3.5 exercise',
        'random_number_ps',
        "publishes random geometry_msgs/Twist velocities to turtlesim's /turtle1/cmd_vel",
    ),
    Exercise(
        'temp_server',
        '3.6.3',
        'olive_srvcli',
        'the temp_conversion service (olive_interfaces/srv/TempConv): Celsius to Kelvin and Fahrenheit',
    ),
    Exercise(
        'temp_client',
        '3.6.3',
        'olive_srvcli',
        'sends its command-line Celsius value to temp_conversion and prints the answer',
    ),
    Exercise(
        'upper_limit',
        '3.7.2',
        'random_number_ps',
        "random_number_publisher's upper_limit parameter: default 100, changed with ros2 param set",
    ),
    Exercise(
        'lower_limit',
        '3.7.2 exercise',
        'random_number_ps',
        'a parameter for the lower bound of random_number_publisher',
    ),
    Exercise(
        'turtle_launch',
        '3.9',
        'olive_launch',
        "olive_launch's launch file starts two turtlesim nodes, turtle1 and turtle2",
    ),
    Exercise(
        'imu_turtle',
        '4.3.2',
        'olive_imu',
        "the IMU's pitch drives the turtle forward, its yaw turns it (/turtle1/cmd_vel)",
    ),
    Exercise(
        'imu_turtle_launch',
        '4.3.2 +',
        'olive_imu',
        'a launch file of olive_imu that starts turtlesim_node and imu_turtle',
        extra=True,
    ),
    Exercise(
        'imu_turtle_speed',
        '4.3.2 +',
        'olive_imu',
        "a parameter of imu_turtle that adjusts the turtle's speed",
        extra=True,
    ),
    Exercise(
        'pid_testing',
        '4.4, 5.3',
        'olive_servo',
        'appendix 5.3: enables the pan torque, then goals 1.57 and 0.0 rad every 3 s',
    ),
    Exercise(
        'control_servo',
        '4.4',
        'olive_servo',
        'enables the pan torque, then publishes a sine of goal positions every 0.01 s',
    ),
    Exercise(
        'control_servo_torque_off',
        '4.4 +',
        'olive_servo',
        'control_servo disables the torque when it is stopped with Ctrl-C',
        extra=True,
    ),
    Exercise(
        'keyboard_servos',
        '4.4.1',
        'olive_servo',
        'arrow keys move the pan (left/right) and tilt (up/down) goals, within bounds',
    ),
    Exercise(
        'imu_control_robot',
        '4.4.1',
        'olive_servo',
        'the IMU points the pan/tilt head: goals follow yaw and pitch, within bounds',
    ),
    Exercise(
        'display_camera',
        '4.5',
        'olive_camera',
        "shows the camera's CompressedImage frames with cv2.imshow, with a best-effort QoS",
    ),
)

BY_ID = {exercise.id: exercise for exercise in EXERCISES}


def find(exercise_id: str) -> Exercise | None:
    return BY_ID.get(exercise_id)


def closest(exercise_id: str) -> str | None:
    """The known id most like an unknown one, or None when none is close."""
    matches = difflib.get_close_matches(exercise_id, BY_ID, n=1, cutoff=0.5)
    return matches[0] if matches else None


def unknown_id_message(exercise_id: str) -> str:
    suggestion = closest(exercise_id)
    hint = f"; did you mean '{suggestion}'?" if suggestion else ''
    return f"owl check: unknown exercise '{exercise_id}'{hint} ('owl check --list' lists them)"


def listing() -> list[str]:
    """The lines of `owl check --list`: id, section, description."""
    width = max(len(e.id) for e in EXERCISES)
    section_width = max(len(e.section) for e in EXERCISES)
    return [f'{e.id:<{width}}  {e.section:<{section_width}}  {e.description}' for e in EXERCISES]
