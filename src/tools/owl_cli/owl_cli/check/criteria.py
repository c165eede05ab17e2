"""The judgements of `owl check`, from measured values to a passed or failed criterion with a hint.

No ROS here: ros.py measures, these functions decide, so each decision is unit-tested.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Sequence

from owl_cli.check.report import Criterion

# Velocities or goals smaller than this count as "nothing" (the IMU's own noise stays far below).
STILL = 0.05


def kelvin(temp_c: float, temp_k: float) -> Criterion:
    """temp_conversion's kelvin answer temp_k for temp_c, against formula (2): K = °C + 273.15."""
    expected = temp_c + 273.15
    return Criterion(
        f'temp_conversion: {temp_c:g} °C is {expected:g} K (formula 2)',
        math.isclose(temp_k, expected, abs_tol=1e-6),
        'temp_k must be temp_c + 273.15',
        f'answered {temp_k:g} K',
    )


def fahrenheit(temp_c: float, temp_f: float) -> Criterion:
    """temp_conversion's Fahrenheit answer temp_f for temp_c, against formula (1): °F = °C * 9/5 + 32.

    The hint names the listing's typo (9 / 2 instead of 9 / 5) when that is what the answer used.
    """
    expected = temp_c * 9 / 5 + 32
    passed = math.isclose(temp_f, expected, abs_tol=1e-6)
    if math.isclose(temp_f, temp_c * 9 / 2 + 32, abs_tol=1e-6):
        hint = "that is the listing's temp_c * 9 / 2 + 32, a typo: formula (1) is °F = °C * 9/5 + 32"
    else:
        hint = 'temp_f must be temp_c * 9 / 5 + 32 (formula 1)'
    return Criterion(
        f'temp_conversion: {temp_c:g} °C is {expected:g} °F (formula 1)',
        passed,
        hint,
        f'answered {temp_f:g} °F',
    )


def rate(stamps: Sequence[float]) -> float:
    """Messages per second over the stamps (monotonic seconds) of consecutive messages."""
    if len(stamps) < 2 or stamps[-1] <= stamps[0]:
        return 0.0
    return (len(stamps) - 1) / (stamps[-1] - stamps[0])


def outside(values: Sequence[float], low: float, high: float) -> list[float]:
    """The values not within low..high."""
    return [v for v in values if not low <= v <= high]


def range_decided(values: Sequence[float], low: float, high: float, enough: int) -> bool:
    """Whether in_range over values is decided before more arrive: enough did, or one is outside.

    More values cannot bring one outside low..high back in: in_range fails from that one on.
    """
    return len(values) >= enough or bool(outside(values, low, high))


def in_range(what: str, values: Sequence[float], low: float, high: float, hint: str) -> Criterion:
    """Whether every one of values lies in low..high; it fails when none arrived, too."""
    detail = f'{len(values)} values from {min(values):g} to {max(values):g}' if values else 'no values'
    return Criterion(
        f'{what} stay within {low:g}..{high:g}',
        bool(values) and not outside(values, low, high),
        hint if values else f'no {what} arrived',
        detail,
    )


def turtle_response(motion: str, linear: float, angular: float) -> Criterion:
    """How the turtle answers an IMU tilted forward (motion 'pitch') or turned left ('yaw').

    linear and angular are the mean linear.x and angular.z while the IMU held that orientation.
    REP 103: pitching forward is a positive pitch, turning left a positive yaw; turtlesim drives
    forward for a positive linear.x and turns left for a positive angular.z.
    """
    detail = f'linear.x {linear:+.2f}, angular.z {angular:+.2f}'
    if motion == 'pitch':
        text = 'the turtle drives forward when the IMU pitches forward'
        wanted, other, name = linear, angular, 'pitch'
        wrong_way = (
            'the turtle goes backwards when the IMU pitches forward: check the sign of pitch '
            '(linear.x must grow with pitch)'
        )
    else:
        text = 'the turtle turns left when the IMU turns left (yaw)'
        wanted, other, name = angular, linear, 'yaw'
        wrong_way = (
            'the turtle turns right when the IMU turns left: check the sign of yaw '
            '(angular.z must grow with yaw)'
        )
    if abs(other) > STILL and abs(other) >= abs(wanted):
        return Criterion(
            text,
            False,
            (
                f'the turtle {"turns" if motion == "pitch" else "drives"} when only the {name} changes: '
                'pitch must set linear.x (the speed) and yaw angular.z (the turn rate); are pitch and yaw '
                'swapped?'
            ),
            detail,
        )
    if wanted < -STILL:
        return Criterion(text, False, wrong_way, detail)
    if wanted <= STILL:
        moved = 'pitches forward' if motion == 'pitch' else 'turns left'
        return Criterion(
            text,
            False,
            f'the turtle does not move when the IMU {moved}: use the {name} '
            'angle from equations (3) for the velocity',
            detail,
        )
    return Criterion(text, True, '', detail)


def standing_still(linear: float, angular: float) -> Criterion:
    """Whether the turtle's velocities stay within STILL while the IMU is level and faces ahead."""
    return Criterion(
        'the turtle stands still while the IMU is level and faces ahead',
        abs(linear) <= STILL and abs(angular) <= STILL,
        'with roll, pitch and yaw all 0 the velocities must be 0: use pitch and yaw from '
        'equations (3), not the raw quaternion',
        f'linear.x {linear:+.2f}, angular.z {angular:+.2f}',
    )


def follows(what: str, goal: float, angle: float, tolerance: float = 0.15) -> Criterion:
    """A servo goal that must equal an IMU angle (within the bounds)."""
    return Criterion(
        f'{what}',
        math.isclose(goal, angle, abs_tol=tolerance),
        '',
        f'goal {goal:+.2f} rad for {angle:+.2f} rad',
    )


def bounded_goal(servo: str, goals: Sequence[float], low: float, high: float, cause: str) -> Criterion:
    """Goals of a servo that something (a key held, the IMU turned far) pushed toward its limit."""
    text = f"{servo} goals stay within the servo's range {low:g}..{high:g} rad when {cause}"
    if not goals:
        return Criterion(text, False, f'no {servo} goal arrived while {cause}')
    beyond = max(goals, key=lambda g: max(g - high, low - g))
    passed = low - 1e-3 <= min(goals) and max(goals) <= high + 1e-3
    return Criterion(
        text,
        passed,
        (
            f'a goal of {beyond:+.2f} rad would drive the {servo} servo past its range: add upper and lower '
            'bounds to the goals (max(low, min(high, goal)))'
        ),
        f'goals {min(goals):+.2f}..{max(goals):+.2f} rad',
    )


def oscillates(values: Sequence[float], least_swing: float = 0.2) -> bool:
    """Whether values swing by least_swing and turn back at least once (a sine, not a ramp)."""
    if len(values) < 3 or max(values) - min(values) < least_swing:
        return False
    rising = None
    for previous, current in itertools.pairwise(values):
        if abs(current - previous) < 1e-6:
            continue
        now_rising = current > previous
        if rising is not None and now_rising != rising:
            return True
        rising = now_rising
    return False


def lag_behind_moving_target(position: float, at: float, start: float, speed: float,
                             left_between: tuple[float, float]) -> float:
    """How far position, measured at time at, is from a target that left start at speed.

    When it left is known only within left_between (the call that set it going took a while), so
    this is the smallest distance over that interval: the doubt is ours, not the tracker's.
    """
    reach = sorted(start + speed * (at - left) for left in left_between)
    if reach[0] <= position <= reach[1]:
        return 0.0
    return min(abs(position - reach[0]), abs(position - reach[1]))


def mean(values: Sequence[float]) -> float:
    """The arithmetic mean of values; 0.0 for none."""
    return sum(values) / len(values) if values else 0.0


def tail_lines(output: str, count: int = 5) -> str:
    """The last count non-blank lines of a process's output joined by ' | ', for a hint on one line."""
    lines = [line for line in output.splitlines() if line.strip()]
    return ' | '.join(lines[-count:]) if lines else '(no output)'


def currency_answers(at_100: Sequence[float], at_250: Sequence[float]) -> list[Criterion]:
    """The amounts a currency service answered for 100 and for 250 euros (its number fields)."""
    amounts = [a for a in at_100 if a > 0]
    three = Criterion(
        'answers 100 euros in three currencies (three amounts above 0)',
        len(amounts) >= 3,
        'the response needs one number per currency (e.g. dollars, pounds, swiss_francs), each '
        'the euros times its rate',
        f'answered {", ".join(f"{a:g}" for a in at_100)}',
    )
    proportional = bool(at_100) and len(at_100) == len(at_250) and all(
        math.isclose(b, a * 2.5, rel_tol=0.01, abs_tol=0.02) for a, b in zip(at_100, at_250, strict=True)
    )
    scaled = Criterion(
        'each amount grows with the euros (250 euros give 2.5 times the amounts of 100)',
        proportional,
        'multiply the request\'s euros by a fixed rate for each currency',
        f'answered {", ".join(f"{a:g}" for a in at_250)} for 250 euros',
    )
    different = Criterion(
        'the three currencies have different rates',
        len({round(a, 2) for a in amounts}) >= 3,
        'dollar, pound and Swiss franc each have their own rate: one amount per currency',
        f'{", ".join(f"{a:g}" for a in amounts)}',
    )
    return [three, scaled, different]


def factorial_answer(n: int, values: Sequence[float]) -> Criterion:
    """A factorial service's number fields for the request n."""
    expected = math.factorial(n)
    if n == 0:
        hint = '0! is 1 (the empty product): start the product at 1'
    else:
        hint = f'{n}! is 1 * 2 * ... * {n}: multiply, in a loop or with math.factorial({n})'
    return Criterion(
        f'the factorial of {n} is {expected}',
        any(v == expected for v in values),
        hint,
        f'answered {", ".join(str(v) for v in values) or "no number"}',
    )


NUMBER = re.compile(r'[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?')


def numbers_in(text: str) -> list[float]:
    """Every number printed in text (log time stamps included, which never match an answer)."""
    return [float(m) for m in NUMBER.findall(text)]


def slope(samples: Sequence[tuple[float, float]]) -> float:
    """The least-squares rate of change (value per second) of (time, value) samples, as a magnitude."""
    if len(samples) < 3:
        return 0.0
    times = [t for t, _ in samples]
    values = [v for _, v in samples]
    mean_t, mean_v = mean(times), mean(values)
    spread = sum((t - mean_t) ** 2 for t in times)
    if spread == 0:
        return 0.0
    return abs(sum((t - mean_t) * (v - mean_v) for t, v in samples) / spread)
