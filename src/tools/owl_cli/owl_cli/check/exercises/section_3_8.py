"""Section 3.8: actions, sent by hand to turtlesim."""

from __future__ import annotations

from owl_cli.check.catalogue import TERMINAL, Section

SECTION = Section()


SECTION.by_hand(
    'turtle_actions',
    '3.8',
    'turtlesim',
    "rotate_absolute goals with turtle_teleop_key's keys and ros2 action send_goal",
    TERMINAL,
)
