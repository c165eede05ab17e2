"""Sections 4.6 and 4.7 (docs/course, our text where the course has none) against the kit and the tools."""

import re
from pathlib import Path

import pytest
from olive_kit.description import SERVO_RANGES

pytestmark = pytest.mark.no_processes

COURSE = Path(__file__).parents[1] / 'docs' / 'course'
SECTIONS = sorted(COURSE.glob('4.*.md'))
# a command as the text shows it: a line of a code block, or a `...` span
COMMAND = re.compile(r'^\$ (.+)$|`([^`\n]+)`', re.M)


def commands(text: str) -> list[str]:
    return [' '.join((block or span).split()) for block, span in COMMAND.findall(text.replace('\n  ', ' '))]


def test_every_parameter_given_on_a_command_line_comes_after_ros_args():
    assert SECTIONS, COURSE
    for section in SECTIONS:
        for command in commands(section.read_text()):
            if re.search(r'(^| )-p \w+:=', command):
                assert re.search(r'--ros-args( .*)? -p ', command), f'{section.name}: {command}'


def test_the_servos_ranges_are_the_kits():
    text = ' '.join((COURSE / '4.6-object-tracking.md').read_text().split())
    pan_low, pan_high = SERVO_RANGES['pan']
    tilt_low, tilt_high = SERVO_RANGES['tilt']
    assert f'the pan servo turns from {pan_low:g} to {pan_high:g} rad' in text
    assert f'the tilt servo from {tilt_low:g} rad (up) to {tilt_high:g} rad (down' in text
    gestures = ' '.join((COURSE / '4.7-gesture-control.md').read_text().split())
    assert f'pan {pan_low:g} to {pan_high:g} rad, tilt {tilt_low:g} to {tilt_high:g} rad' in gestures


def test_the_students_package_goes_in_their_workspace_not_beside_the_reference_solution():
    text = ' '.join((COURSE / '4.6-object-tracking.md').read_text().split())
    assert 'In the `src` folder of your workspace (`~/Workspaces/ros2_olive_ws/src`' in text
    assert "Owl Kit Lab's own `src/` already holds a package of that name" in text
    assert 'in your workspace, from section 4.6' in (COURSE / '4.7-gesture-control.md').read_text()
