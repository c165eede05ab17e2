"""The robot view's servo controls as plain data (node-free), checked before anything reaches ROS.

What a page's `set_gains`, `torque` and `goal` commands may ask; each refusal is one ApiError line.

The limits are the kit's own: the gains' ranges are the kit's (olive_kit.description.GAIN_LIMITS,
the ranges its parameters declare), a goal's range is the one the kit's launch gives each servo
(olive_kit.description.SERVO_RANGES), so a goal outside it is refused here instead of clamped by the servo.
"""

from __future__ import annotations

import json
import math
from typing import Any

from olive_kit.description import GAIN_LIMITS, SERVO_RANGES, goal_topic, node_name, servo_topic
from owl_web import codec
from owl_web.codec import ApiError

SERVOS = tuple(SERVO_RANGES)  # pan, tilt
GAINS = tuple(GAIN_LIMITS)  # kp, ki, kd
# The appendix 5.3 script's two goals (it publishes 1.57 for pi/2).
APPENDIX_GOALS = (0.0, 1.57)


def servo_node(servo: str) -> str:
    """The servo's node, whose parameters kp, ki and kd are (the course's /olive_servo_pan_dcm_srv)."""
    return '/' + node_name('servo', servo)


def servo_name(arguments: dict[str, Any]) -> str:
    """The command's "servo", one of SERVOS; else ApiError 404 naming the known ones (and a near miss)."""
    servo = arguments['servo']
    if servo not in SERVOS:
        near = servo.lower() if isinstance(servo, str) else None
        hint = f" (did you mean '{near}'?)" if near in SERVOS else ''
        raise ApiError(404, f'unknown servo {json.dumps(servo)[:80]}{hint}; known: {", ".join(SERVOS)}')
    return servo


def number(value: Any, what: str, low: float, high: float) -> float:
    """A finite JSON number within low..high."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ApiError(400, f'{what} must be a number, got {json.dumps(value)[:80]}')
    if not math.isfinite(value):
        raise ApiError(400, f'{what} must be finite, got {value}')
    if not low <= value <= high:
        raise ApiError(400, f'{what} must be within {low:g}..{high:g}, got {value:g}')
    return float(value)


def gains_request(arguments: dict[str, Any]) -> tuple[str, dict[str, float]]:
    """A `set_gains` command as (servo, {gain: value}), each gain within its range.

    The command is {"servo": "pan", "kp": 1.0, "ki": 0, "kd": 0}, with at least one gain.
    """
    codec.check_keys(arguments, ('servo', *GAINS), required=('servo',))
    servo = servo_name(arguments)
    gains = {name: number(arguments[name], f'{servo} {name}', 0.0, GAIN_LIMITS[name])
             for name in GAINS if name in arguments}
    if not gains:
        raise ApiError(400, f'set_gains needs at least one of {", ".join(GAINS)}')
    return servo, gains


def torque_request(arguments: dict[str, Any]) -> tuple[str, bool]:
    """A `torque` command ({"servo": "pan", "enabled": true}): (servo, enabled)."""
    codec.check_keys(arguments, ('servo', 'enabled'), required=('servo', 'enabled'))
    return servo_name(arguments), codec.boolean(arguments['enabled'], '"enabled"')


def goal_request(arguments: dict[str, Any]) -> tuple[str, float]:
    """A `goal` command ({"servo": "pan", "position": 1.57}) as (servo, position in rad).

    The position must be within the servo's range.
    """
    codec.check_keys(arguments, ('servo', 'position'), required=('servo', 'position'))
    servo = servo_name(arguments)
    low, high = SERVO_RANGES[servo]
    return servo, number(arguments['position'], f'the {servo} goal', low, high)


def ball_request(arguments: dict[str, Any]) -> tuple[float, float]:
    """A `place_ball` command ({"azimuth": 0.3, "elevation": -0.1}, rad) as (azimuth, elevation).

    The azimuth is taken round the circle into -pi..pi; whether the elevation is in the ball's world
    is the camera's to say.
    """
    codec.check_keys(arguments, ('azimuth', 'elevation'), required=('azimuth', 'elevation'))
    azimuth = number(arguments['azimuth'], "the ball's azimuth", -math.inf, math.inf)
    elevation = number(arguments['elevation'], "the ball's elevation", -math.inf, math.inf)
    return math.remainder(azimuth, 2 * math.pi), elevation


def appendix_goals(servo: str) -> list[float]:
    """The appendix's goals, 0 and 1.57 rad, each brought within the servo's range.

    The tilt servo's top is 0.9 rad: the camera would hit the base.
    """
    low, high = SERVO_RANGES[servo]
    return [min(high, max(low, goal)) for goal in APPENDIX_GOALS]


def control_limits() -> dict[str, Any]:
    """What the page's controls offer: the gains' ranges, and each servo's range, goal buttons and names.

    The names (its goal topic, its torque services) are the kit's, for the controls' tooltips.
    """
    return {'gains': dict(GAIN_LIMITS),
            'servos': {servo: {'range': list(SERVO_RANGES[servo]), 'goals': appendix_goals(servo),
                               'goal_topic': goal_topic(servo),
                               'torque_services': [servo_topic(servo, name)
                                                   for name in ('setTorqueEnable', 'setTorqueDisable')]}
                       for servo in SERVOS}}
