"""How `ros2 doctor` prints: reports as aligned key/value lines, findings as warnings on stderr."""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2doctor.api import Report

MIN_PADDING = 8


def format_report(report: Report) -> str:
    """A report's text: a blank line, its name indented by 3, then `key<padding>: value` lines.

    Keys are padded to the longest key plus 4 (at least MIN_PADDING), as upstream prints them.
    """
    longest = max((len(key) for key, _ in report.items), default=0)
    padding = longest + 4 if longest >= MIN_PADDING else MIN_PADDING
    lines = ['', f'   {report.name}']
    lines += [f'{key:{padding}}: {value}' for key, value in report.items]
    return '\n'.join(lines)


def format_print(report: Report) -> None:
    """Print a report (see format_report)."""
    print(format_report(report))


def doctor_warn(message: str) -> None:
    """Say a finding on stderr, in the shape of upstream's (Python warning) lines."""
    print(f'UserWarning: {message}', file=sys.stderr)


def doctor_error(message: str) -> None:
    """Say a failing finding on stderr."""
    doctor_warn(f'ERROR: {message}')
