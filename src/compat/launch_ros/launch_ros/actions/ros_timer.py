"""ROSTimer (humble: RosTimer): TimerAction whose period is meant on the ROS clock."""

from launch.actions import TimerAction


class ROSTimer(TimerAction):
    """A TimerAction on the ROS clock.

    This launch runs no ROS node, so the ROS clock is the system clock: the period is wall time,
    which equals ROS time unless the launched system uses simulated time (use_sim_time).
    """


RosTimer = ROSTimer
