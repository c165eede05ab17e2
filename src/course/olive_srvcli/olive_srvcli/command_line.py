"""The clients' command line: one number, checked before any ROS work starts.

A bad command line ends the client with one line on stderr and exit code 2 (the code argparse
uses), so a student sees what to type instead of a traceback from `float(sys.argv[1])`.
"""

import math
import sys
from collections.abc import Callable
from typing import TypeVar

from rclpy.utilities import remove_ros_args

from olive_srvcli.conversions import check_celsius

Value = TypeVar('Value')
Number = TypeVar('Number', int, float)


class UsageError(Exception):
    """The command line cannot become a request; the message says why."""


def number_argument(argv: list[str], what: str, kind: type[Number]) -> Number:
    """The single command-line argument as a number of the given kind (a float must be finite)."""
    if len(argv) != 1:
        raise UsageError(f'expected exactly one argument, {what}; got {len(argv)}')
    text = argv[0]
    try:
        value = kind(text)
    except ValueError:
        article = 'an integer' if kind is int else 'a number'
        raise UsageError(f"'{text}' is not {article}") from None
    if kind is float and not math.isfinite(value):
        raise UsageError(f"'{text}' is not a finite number")
    return value


def celsius_argument(argv: list[str]) -> float:
    temp_c = number_argument(argv, 'a temperature in Celsius', kind=float)
    problem = check_celsius(temp_c)
    if problem:
        raise UsageError(problem)
    return temp_c


def euros_argument(argv: list[str]) -> float:
    euros = number_argument(argv, 'an amount in euros', kind=float)
    if euros < 0:
        raise UsageError(f'the amount must not be negative, got {euros}')
    return euros


def integer_argument(argv: list[str]) -> int:
    # Range checks are the factorial server's job: it answers success=false with the reason.
    n = number_argument(argv, 'an integer', kind=int)
    if not -2**63 <= n < 2**63:
        raise UsageError(f'{n} does not fit the 64-bit integer of the request')
    return n


def argument_or_exit(parse: Callable[[list[str]], Value], usage: str, args: list[str] | None = None) -> Value:
    """The value parse() makes of the command line; for a bad one, print the reason and exit with code 2.

    parse gets the arguments after the program's name, without --ros-args. On a UsageError this
    prints `<program>: error: <reason> (usage: <program> <usage>)` to stderr and exits with code 2.

    args is main()'s args: None means sys.argv, as rclpy.init takes it.
    """
    argv = remove_ros_args(args=sys.argv if args is None else args)
    program = argv[0].rsplit('/', 1)[-1] if argv else 'client'
    try:
        return parse(argv[1:])
    except UsageError as error:
        print(f'{program}: error: {error} (usage: {program} {usage})', file=sys.stderr)
        sys.exit(2)
