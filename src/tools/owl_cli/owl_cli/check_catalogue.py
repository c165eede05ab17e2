"""The exercises and projects of course sections 3.4 to 4.5, the "+" extras included.

Each has an id (the course's executable name where there is one, else a short name), its section,
the package it lives in and a one-line description. Exercises done by hand at a terminal or on the
hardware (3.6.1's service calls, 3.7.1's colour changes, 3.8's action goals, 4.3's debug GUI, 4.4's
PID tuning) leave nothing behind to check: they are listed with the reason (`not_checked`).
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
    not_checked: str = ''  # why there is nothing to check (an exercise done by hand at a terminal)
    # The course's "choose one of the following exercises": --all checks only those of the group
    # whose executable the workspace has.
    choice: str = ''

    @property
    def checkable(self) -> bool:
        return not self.not_checked


TERMINAL = 'typed at a terminal (ros2 and rqt commands), it leaves nothing in a workspace to check'

EXERCISES: tuple[Exercise, ...] = (
    Exercise(
        'test_package',
        '3.4',
        'test_package',
        'ros2 pkg create test_package --build-type ament_python: the package layout colcon builds',
    ),
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
        'turtle_services',
        '3.6.1 exercises',
        'turtlesim',
        "spawn, kill and teleport turtlesim's turtles with ros2 service call and rqt's Service Caller",
        not_checked=TERMINAL,
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
        'currency_server',
        '3.6 exercise',
        'olive_srvcli',
        'a service that converts euros into three currencies (choose it or factorial)',
        choice='3.6',
    ),
    Exercise(
        'currency_client',
        '3.6 exercise',
        'olive_srvcli',
        'sends its command-line euros to the currency service and prints the three amounts',
        choice='3.6',
    ),
    Exercise(
        'factorial_server',
        '3.6 exercise',
        'olive_srvcli',
        'a service that answers the factorial of an integer (choose it or currency)',
        choice='3.6',
    ),
    Exercise(
        'factorial_client',
        '3.6 exercise',
        'olive_srvcli',
        'sends its command-line integer to the factorial service and prints the answer',
        choice='3.6',
    ),
    Exercise(
        'turtle_background',
        '3.7.1 exercise',
        'turtlesim',
        "turtlesim's background yellow, then black, with ros2 param set",
        not_checked=TERMINAL,
    ),
    Exercise(
        'params_file',
        '3.7.1',
        '',
        'a parameter file (ros2 param dump, edited) that --ros-args --params-file loads at start-up',
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
        'turtle_actions',
        '3.8',
        'turtlesim',
        "rotate_absolute goals with turtle_teleop_key's keys and ros2 action send_goal",
        not_checked=TERMINAL,
    ),
    Exercise(
        'turtle_launch',
        '3.9',
        'olive_launch',
        "olive_launch's launch file starts two turtlesim nodes, turtle1 and turtle2",
    ),
    Exercise(
        'imu_debug_gui',
        '4.3 exercise',
        'olive_imu',
        "the IMU's debug web GUI: watch roll, pitch and yaw while turning the IMU by hand",
        not_checked="done by hand on the IMU's web page (the module's or olive_sim's); nothing is left",
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
        'imu_turtle_topic',
        '4.3.2 +',
        'olive_imu',
        "a parameter of imu_turtle for the name of the IMU's topic",
        extra=True,
    ),
    Exercise(
        'pid_tuning',
        '4.4 exercises',
        'olive_servo',
        "tune the pan servo's Kp, Ki, Kd with ros2 param set and watch the overshoot",
        not_checked=TERMINAL,
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
        'control_servo_frequency',
        '4.4 +',
        'olive_servo',
        'a parameter of control_servo for the publishing frequency',
        extra=True,
    ),
    Exercise(
        'keyboard_servos',
        '4.4.1',
        'olive_servo',
        'arrow keys move the pan (left/right) and tilt (up/down) goals, within bounds',
    ),
    Exercise(
        'keyboard_servos_torque',
        '4.4.1 +',
        'olive_servo',
        "keyboard_servos enables both servos' torque at start and disables it when it stops",
        extra=True,
    ),
    Exercise(
        'keyboard_servos_speed',
        '4.4.1 +',
        'olive_servo',
        'a parameter of keyboard_servos that adjusts the speed of the servos',
        extra=True,
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
    Exercise(
        'robot_camera_launch',
        '4.5 +',
        'olive_camera',
        'a launch file that starts imu_control_robot and display_camera',
        extra=True,
    ),
)

BY_ID = {exercise.id: exercise for exercise in EXERCISES}


CHECKABLE = tuple(e for e in EXERCISES if e.checkable)


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


def not_checked_message(exercise: Exercise) -> str:
    return f'owl check: {exercise.id} (section {exercise.section}) is not checked: {exercise.not_checked}'


def listing() -> list[str]:
    """The lines of `owl check --list`: id, section, description (and why, for one not checked)."""
    width = max(len(e.id) for e in EXERCISES)
    section_width = max(len(e.section) for e in EXERCISES)
    return [
        f'{e.id:<{width}}  {e.section:<{section_width}}  {e.description}'
        + ('' if e.checkable else ' [not checked: done by hand]')
        for e in EXERCISES
    ]
